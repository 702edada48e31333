#pragma once
// reference and reference-ms: the reference baker's lightmaps of each frame's volume for that frame's view
// (exact single scattering, or with the higher orders path-traced: reference::ScatteredLightmaps), uploaded
// before the shading (stages "bake/…").
#include "reference/scattered_lightmaps.h"
#include "runtime/lightmap_source.h"

namespace sixway::modes {

class BakedLightmaps : public runtime::LightmapSource {
 public:
  // `multiple`: the higher orders' tracing; its seed becomes the scene's render.seed + frame.
  BakedLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache, const scene::Scene& scene,
                 reference::Scattering scattering, const reference::MultipleScattering& multiple);

  render::ImagePlane update(runtime::RealtimeFrame& frame, const runtime::SourceFrame& current) override;
  std::vector<gpu::StageTime> stageTimes() const override;

 protected:
  BakedLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache, const scene::Scene& scene,
                 reference::Scattering scattering, const reference::MultipleScattering& multiple,
                 runtime::FrameStages stages);
  // The lightmaps of `current`'s volume seen from `camera` over `plane` into the frame's.
  void bake(runtime::RealtimeFrame& frame, const runtime::SourceFrame& current, const render::Camera& camera,
            const render::ImagePlane& plane);

 private:
  scene::Smoke smoke_;
  uint32_t seed_;  // the scene's render.seed
  reference::Scattering scattering_;
  reference::MultipleScattering multiple_;
  reference::ScatteredLightmaps baker_;
};

}  // namespace sixway::modes
