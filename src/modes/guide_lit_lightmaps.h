#pragma once
// guide-lit: the guide's mean light as all six lightmaps and its alpha, no network
// (reference::GuideLightmaps, stage "guide lightmaps"): the evaluation's "guide only" baseline.
#include "reference/guide_lightmaps.h"
#include "runtime/lightmap_source.h"

namespace sixway::modes {

class GuideLitLightmaps : public runtime::LightmapSource {
 public:
  GuideLitLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache, const scene::Scene& scene);

  void record(gpu::Sequence& sequence, runtime::RealtimeFrame& frame) override;

 private:
  reference::GuideLightmaps lightmaps_;
};

}  // namespace sixway::modes
