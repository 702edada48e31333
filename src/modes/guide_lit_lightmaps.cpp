#include "modes/guide_lit_lightmaps.h"

namespace sixway::modes {

GuideLitLightmaps::GuideLitLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache,
                                     const scene::Scene& scene)
    : lightmaps_(context, cache, uint32_t(render::GuideSettings::fromScene(scene).lights.size())) {}

void GuideLitLightmaps::record(gpu::Sequence& sequence, runtime::RealtimeFrame& frame) {
  lightmaps_.record(sequence, frame.guide(), frame.lightmaps());
}

}  // namespace sixway::modes
