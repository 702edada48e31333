#pragma once
// reference-fit: the six maps a six-way material can best use (reference::FittedLightmaps) of each frame's
// volume for that frame's view, uploaded before the shading (stages "fit/…", summed over the fit's bakes).
#include "reference/fitted_lightmaps.h"
#include "runtime/lightmap_source.h"

namespace sixway::modes {

class FittedLightmapSource : public runtime::LightmapSource {
 public:
  // `multiple`: each bake's higher orders; its seed becomes the scene's render.seed + frame. `directions`:
  // how many (reference::fitDirections).
  FittedLightmapSource(const gpu::Context& context, const gpu::PipelineCache& cache,
                       const scene::Scene& scene, const reference::MultipleScattering& multiple,
                       int directions);

  render::ImagePlane update(runtime::RealtimeFrame& frame, const runtime::SourceFrame& current) override;
  std::vector<gpu::StageTime> stageTimes() const override;

 private:
  scene::Smoke smoke_;
  uint32_t seed_;  // the scene's render.seed
  reference::MultipleScattering multiple_;
  reference::FittedLightmaps baker_;
};

}  // namespace sixway::modes
