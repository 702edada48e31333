#include "modes/baked_lightmaps.h"

namespace sixway::modes {

BakedLightmaps::BakedLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache,
                               const scene::Scene& scene, reference::Scattering scattering,
                               const reference::MultipleScattering& multiple)
    : BakedLightmaps(context, cache, scene, scattering, multiple, runtime::FrameStages::All) {}

BakedLightmaps::BakedLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache,
                               const scene::Scene& scene, reference::Scattering scattering,
                               const reference::MultipleScattering& multiple, runtime::FrameStages stages)
    : LightmapSource(stages),
      smoke_(scene.smoke),
      seed_(scene.render.seed),
      scattering_(scattering),
      multiple_(multiple),
      baker_(context, cache) {}

render::ImagePlane BakedLightmaps::update(runtime::RealtimeFrame& frame,
                                          const runtime::SourceFrame& current) {
  bake(frame, current, current.camera, current.billboard);
  return current.billboard;
}

void BakedLightmaps::bake(runtime::RealtimeFrame& frame, const runtime::SourceFrame& current,
                          const render::Camera& camera, const render::ImagePlane& plane) {
  reference::BakeSettings bake;
  bake.width = bake.height = int(frame.lightmapSize());
  reference::MultipleScattering multiple = multiple_;
  multiple.seed = seed_ + uint32_t(current.index);  // independent noise frame to frame
  frame.lightmaps().upload(baker_.bake(current.volume, smoke_, camera, plane, bake, scattering_, multiple));
}

std::vector<gpu::StageTime> BakedLightmaps::stageTimes() const {
  std::vector<gpu::StageTime> times;
  for (const gpu::StageTime& t : baker_.stageTimes()) times.push_back({"bake/" + t.name, t.milliseconds});
  return times;
}

}  // namespace sixway::modes
