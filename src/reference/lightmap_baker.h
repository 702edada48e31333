#pragma once
// The reference six-way baker (single scattering, no noise): the eight channels of docs/conventions.md,
// "Channels and packing" for a camera, a billboard and a density volume. For each of the six camera-relative
// lights a compute pass integrates the optical depth toward the light on a light-space grid
// (light_depth.comp); then one fine view-ray march accumulates σ_s · T_view · T_light · π · p_HG for the six
// lights, alpha = 1 − T_view and the emission (sixway_march.comp), skipping empty bricks (majorant.comp). The
// method and its normalisation: docs/reference-rendering.md.
#include <array>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/sequence.h"
#include "io/image.h"
#include "render/brick_majorants.h"
#include "render/camera.h"
#include "render/light_grid.h"
#include "render/recorded_sequence.h"
#include "render/volume.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Context;
class Pipeline;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::reference {

struct BakeSettings {
  int width = 128, height = 128;   // lightmap pixels
  float stepCells = 0.5f;          // longest quadrature step of view rays and light columns, in cells
  float lightSpacingCells = 1.0f;  // spacing of the light grids, in cells (widened when a grid would not fit)
  float minTransmittance = 1e-6f;  // a view ray stops once less than this of the background shows through
  // Unit directions toward the lights of the six light channels, in world space; unset: the camera's six-way
  // axes (render::sixWayLightDirections). Other directions bake the smoke under lights a six-way material
  // interpolates between (reference/fitted_lightmaps.h).
  std::optional<std::array<glm::vec3, 6>> lights;
};

// The light-grid spacing, in cells, for smoke whose densest cell has the optical depth `cellOpticalDepth`
// (extinction · largest density · cell size): 0.5 / τ cells, within [1/4, 1]. Interpolating the optical
// depth between columns is what biases the baker dark on dense smoke when the lights are oblique to the
// lattice: on a Mantaflow frame with τ = 1.85, columns one cell apart are 7 % dark (45 dB against Cycles),
// 0.27 cells apart 1 % (62 dB) (docs/blender.md, "The Cycles check").
float lightSpacingFor(float cellOpticalDepth);

class LightmapBaker {
 public:
  LightmapBaker(const gpu::Context& context, const gpu::PipelineCache& cache);
  ~LightmapBaker();

  // The eight channels (sixWayChannelNames(), linear, premultiplied) of `volume` lit from the six directions
  // of `camera`, over the `billboard` rectangle of its image plane. Throws io::InputError for settings out
  // of range and an emission ramp with too many keys.
  io::Image bake(const render::Volume& volume, const scene::Smoke& smoke, const render::Camera& camera,
                 const render::ImagePlane& billboard, const BakeSettings& settings);

  // Of the last bake: the light grids (channel order), GPU time per stage, and the optical depths on the
  // grid of light `light`, node index (c · ny + b) · nx + a.
  const std::array<render::LightGrid, 6>& lightGrids() const { return grids_; }
  const std::vector<gpu::StageTime>& stageTimes() const;
  std::vector<float> lightDepths(int light) const;

  static constexpr int kBrickCells = 8;  // side of the empty-space bricks

 private:
  void ensureCapacity(const render::VolumeGrid& grid, uint64_t lightmapValues);

  const gpu::Context* context_;
  std::unique_ptr<render::BrickMajorantPass> majorantPass_;
  std::unique_ptr<gpu::Pipeline> depthPass_, marchPass_;
  gpu::Buffer params_, bricks_, lightmaps_, readback_;
  std::array<gpu::Buffer, 6> depths_;
  std::array<render::LightGrid, 6> grids_;
  render::RecordedSequence sequence_;
  gpu::Sequence* last_ = nullptr;
};

}  // namespace sixway::reference
