#pragma once
// The guiding map, the network's input (docs/conventions.md, "The frame"; docs/real-time-rendering.md,
// "Guiding map"): a coarse, jittered view-ray march of the density over the billboard, into one RGBA16F image
// of (guide, alpha, shell depth, 0 or the fine alpha), and optionally an R32F image of the direct emission.
// The guide is the single-scattered radiance under the surrogate lights, summed, in the bake normalisation;
// the front light's transmittance is the view transmittance, the others read a coarse light-space
// optical-depth grid (the baker's light_depth.comp at a coarse spacing). Recorded once into a gpu::Sequence
// and replayed each frame: update() writes the per-frame values.
#include <cstdint>
#include <memory>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/image.h"
#include "gpu/sequence.h"
#include "render/brick_majorants.h"
#include "render/camera.h"
#include "render/light_grid.h"
#include "render/projection.h"
#include "render/volume.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Context;
class Pipeline;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::render {

struct GuideSettings {
  uint32_t size = 128;              // pixels per side of the (square) guide: the lightmap size
  float stepCells = 3.0f;           // view-ray step, in cells of the volume grid
  float shadowSpacingCells = 2.0f;  // node spacing of the coarse light grids, in cells
  std::vector<scene::GuideLight> lights{scene::GuideLight::Front, scene::GuideLight::Top,
                                        scene::GuideLight::Bottom};
  float shellThreshold = 0.1f;  // alpha at which the shell depth is taken, in (0, 1)
  uint32_t seed = 1;            // of the per-pixel, per-frame jitter
  // > 0: channel A holds the alpha of a second, fine view march of this step (cells; midpoints, not
  // jittered, as the exact baker's alpha); 0: A = 0 (the shipped network's input has no such channel).
  float alphaStepCells = 0.0f;
  // With alphaStepCells > 0: the fine march also integrates the emission reaching the camera directly (the
  // exact baker's emissive channel) into emissionDesc()'s image, a 5th network input.
  bool emission = false;

  // render.lightmap_size, guide_step_voxels, guide_alpha_step_voxels, guide_lights, shell_threshold, seed;
  // the rest default.
  static GuideSettings fromScene(const scene::Scene& scene);
};

class GuidingMap {
 public:
  // Throws io::InputError (source "guiding map") for settings out of range: size 0, step or spacing ≤ 0,
  // no lights or a light twice, threshold outside (0, 1), emission without the fine march.
  GuidingMap(const gpu::Context& context, const gpu::PipelineCache& cache, const GuideSettings& settings);
  ~GuidingMap();

  // The image record() writes: RGBA16F, size × size, storage and sampled.
  gpu::ImageDesc imageDesc() const;
  // The emission image record() writes with settings().emission: R32F, size × size, storage and sampled.
  gpu::ImageDesc emissionDesc() const;

  // Records the stage "guide" (empty-space bricks, light grids, view march) for `volume` into `sequence`;
  // allocates the light grids for the volume's lattice, so a sequence recorded earlier for another lattice
  // must not be replayed. Throws std::invalid_argument unless `guide` has imageDesc()'s size and format and
  // `emission` is given (with emissionDesc()'s) exactly when settings().emission.
  void record(gpu::Sequence& sequence, const Volume& volume, const gpu::Image& guide,
              const gpu::Image* emission = nullptr);

  // The values of one frame, before submitting a sequence that holds record(): the camera, the billboard
  // (billboardBounds(camera, box, 1)), the shell depth range (boxDepthRange(camera, box)), the optics and the
  // frame index that picks the jitter. Uses the lattice of the last record(); throws std::logic_error before
  // the first.
  void update(const Camera& camera, const ImagePlane& billboard, const DepthRange& shellRange,
              const scene::Smoke& smoke, uint32_t frame);

  const GuideSettings& settings() const { return settings_; }
  // How the smoke's opacity builds up along each guide pixel's ray, for the composite with obstacles
  // (sixway_shade.frag): RGBA16F, size × size, the view depths where the opacity first reaches 0.1, 0.35, 0.6
  // and 0.85 (shaders/common/depth.glsl, kOpacityLevels), encoded as the shell depth is; 1 where a level is
  // not reached. record() writes it; a flipbook's is uploaded instead (modes::FlipbookLightmaps).
  gpu::Image& opacityDepths() { return opacityDepths_; }
  const gpu::Image& opacityDepths() const { return opacityDepths_; }

  // Of the last update: the light grids, one per axis of the six-way frame that a guide light other than
  // front lies on, pointing to the first such light in settings().lights; its opposite light uses the same
  // grid.
  const std::vector<LightGrid>& shadowGrids() const { return grids_; }

  static constexpr int kBrickCells = 8;  // side of the empty-space bricks (as the baker's)

 private:
  const gpu::Context* context_;
  GuideSettings settings_;
  std::vector<scene::GuideLight> gridLights_;  // the light each light grid points to, one per axis used
  std::unique_ptr<BrickMajorantPass> majorantPass_;
  std::unique_ptr<gpu::Pipeline> depthPass_, marchPass_;
  gpu::Buffer params_, frame_, bricks_;
  gpu::Image noEmission_;  // bound in place of the emission image without settings().emission (unwritten)
  gpu::Image opacityDepths_;
  std::vector<gpu::Buffer> depths_;  // one per light grid (one placeholder when there are none)
  VolumeGrid grid_;                  // of the last record()
  bool temperature_ = false;         // whether the volume of the last record() has a temperature grid
  float spacing_ = 0.0f;             // light-grid spacing for grid_ (world units)
  int gridNodes_ = 0;                // nodes per axis that any light grid of grid_ stays within
  std::vector<LightGrid> grids_;
};

}  // namespace sixway::render
