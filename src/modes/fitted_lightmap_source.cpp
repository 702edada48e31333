#include "modes/fitted_lightmap_source.h"

namespace sixway::modes {

FittedLightmapSource::FittedLightmapSource(const gpu::Context& context, const gpu::PipelineCache& cache,
                                           const scene::Scene& scene,
                                           const reference::MultipleScattering& multiple, int directions)
    : smoke_(scene.smoke),
      seed_(scene.render.seed),
      multiple_(multiple),
      baker_(context, cache, reference::fitDirections(directions)) {}

render::ImagePlane FittedLightmapSource::update(runtime::RealtimeFrame& frame,
                                                const runtime::SourceFrame& current) {
  reference::BakeSettings bake;
  bake.width = bake.height = int(frame.lightmapSize());
  reference::MultipleScattering multiple = multiple_;
  multiple.seed = seed_ + uint32_t(current.index);  // independent noise frame to frame
  frame.lightmaps().upload(
      baker_.bake(current.volume, smoke_, current.camera, current.billboard, bake, multiple));
  return current.billboard;
}

std::vector<gpu::StageTime> FittedLightmapSource::stageTimes() const {
  std::vector<gpu::StageTime> times;
  for (const gpu::StageTime& t : baker_.stageTimes()) times.push_back({"fit/" + t.name, t.milliseconds});
  return times;
}

}  // namespace sixway::modes
