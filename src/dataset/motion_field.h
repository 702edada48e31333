#pragma once
// The screen-space motion of the smoke over a billboard, for the temporal loss of training
// (docs/dataset-format.md, "Motion field"): per pixel of a guiding map, the smoke shell's world point (the
// guide's shell depth), the flow velocity there, and how far the smoke moved in billboard pixels over an
// interval — motion = pixel(p) − pixel(p − v·Δt), x right, y down; zero where the guide has no shell.
// shaders/render/motion_field.comp does the work; recorded once into a gpu::Sequence after the guiding map,
// update() writes the per-frame values.
#include <cstdint>
#include <memory>

#include "gpu/buffer.h"
#include "gpu/image.h"
#include "gpu/sequence.h"
#include "io/image.h"
#include "render/camera.h"
#include "render/projection.h"
#include "render/volume.h"

namespace sixway::gpu {
class Context;
class Pipeline;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::dataset {

class MotionField {
 public:
  // A size × size field (the guiding map's size). Throws std::invalid_argument for size 0.
  MotionField(const gpu::Context& context, const gpu::PipelineCache& cache, uint32_t size);
  ~MotionField();

  // Records the stage "motion" into `sequence`: reads `guide` (RGBA16F, size²; its B channel is the shell
  // depth) and `velocity` (one vec4 per cell of `velocityGrid`, xyz a velocity in any unit: the lattice's
  // macro buffer holds cells per step), writes the field. Throws std::invalid_argument for a guide of
  // another size or format, or a velocity buffer smaller than the grid.
  void record(gpu::Sequence& sequence, const gpu::Image& guide, const gpu::Buffer& velocity,
              const render::VolumeGrid& velocityGrid);

  // The values of one frame, before submitting: the camera and billboard of the guide, the shell depth range
  // it was encoded with, and how many metres the smoke moves over the interval per unit of the stored
  // velocity (lattice velocity: cell size · steps per frame · frames in the interval).
  void update(const render::Camera& camera, const render::ImagePlane& billboard,
              const render::DepthRange& shellRange, float metresPerVelocityUnit);

  // Of the last submission: channels "motion_x", "motion_y" in billboard pixels.
  io::Image download() const;
  const gpu::Buffer& buffer() const { return motion_; }

 private:
  uint32_t size_;
  std::unique_ptr<gpu::Pipeline> pass_;
  gpu::Buffer params_, motion_;
  render::VolumeGrid velocityGrid_;
};

}  // namespace sixway::dataset
