#pragma once
// Six-way lightmaps with single or multiple scattering (docs/reference-rendering.md, "Multiple
// scattering"). Single: the exact baker. Multiple, split (the default): the exact baker's single
// scattering at full resolution, plus the higher orders (≥ 2, smooth) path-traced at 1/downsample of the
// resolution and upsampled guided by the full-resolution alpha; the emissive channel gains the emission
// scattered by the smoke the same way (its direct part stays the baker's exact one), and alpha, which does
// not depend on scattering, stays the baker's. Multiple, traced: every order (and the emission, direct and
// scattered) path-traced at full resolution (the slow reference the split is measured against).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gpu/sequence.h"
#include "io/image.h"
#include "reference/lightmap_baker.h"
#include "reference/path_tracer.h"
#include "reference/scattering.h"
#include "render/camera.h"
#include "render/volume.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Context;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::reference {

struct MultipleScattering {
  uint32_t samples = 64;  // per traced pixel
  int maxOrders = 64;
  // split: orders ≥ 2 traced at lightmap size / downsample (1, 2, 4 or 8); 2 suits large lightmaps of
  // detailed volumes (docs/reference-rendering.md, "Fast multiple-scattering lightmaps")
  int downsample = 1;
  uint32_t seed = 1;
  bool traceAllOrders = false;  // every order path-traced at full resolution, at pixel centres
};

class ScatteredLightmaps {
 public:
  ScatteredLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache);
  ~ScatteredLightmaps();

  // The eight channels (sixWayChannelNames()) of `volume` from `camera` over `billboard`, as
  // LightmapBaker::bake, with `scattering`. Throws io::InputError for settings out of range.
  io::Image bake(const render::Volume& volume, const scene::Smoke& smoke, const render::Camera& camera,
                 const render::ImagePlane& billboard, const BakeSettings& settings, Scattering scattering,
                 const MultipleScattering& multiple = {});
  // The last bake's exact single scattering (its result, or the part the multiple scattering was added to;
  // empty after a traced-all-orders bake).
  const io::Image& singleScattering() const { return single_; }
  // GPU time of the last bake's stages (the baker's, and "path trace" for multiple scattering).
  const std::vector<gpu::StageTime>& stageTimes() const { return stages_; }
  double milliseconds() const;

 private:
  const gpu::Context* context_;
  const gpu::PipelineCache* cache_;
  LightmapBaker baker_;
  std::unique_ptr<PathTracer> tracer_;  // made on the first multiple-scattering bake
  std::vector<gpu::StageTime> stages_;
  io::Image single_;
};

// The six light channels of `low` (eight channels, (W/d) × (H/d)) brought to W × H and scaled to the
// full-resolution alpha: light = α_full · up(L) / up(α), up bilinear (edges clamped), 0 where up(α) = 0.
// Multiple scattering per unit of opacity is smooth; the ratio keeps it out of pixels the full-resolution
// alpha says are empty. Returns eight channels with alpha and emissive 0.
io::Image upsampleAlphaGuided(const io::Image& low, const io::Image& full);

}  // namespace sixway::reference
