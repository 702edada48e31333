#include "modes/path_traced_smoke.h"

#include <variant>

#include "render/camera.h"

namespace sixway::modes {

PathTracedSmoke::PathTracedSmoke(const gpu::Context& context, const gpu::PipelineCache& cache,
                                 const scene::Scene& scene, const ModeOptions& options)
    : scene_(scene), options_(options), tracer_(context, cache) {
  if (!scene.obstacles.empty()) obstacles_ = std::make_unique<render::ObstacleBvh>(context, scene.obstacles);
}

void PathTracedSmoke::setObstacleMotion(size_t obstacle, std::optional<scene::Motion> motion) {
  if (obstacles_) obstacles_->setMotion(obstacle, std::move(motion));
}

void PathTracedSmoke::composite(io::Image& frame, const runtime::FrameView& view, int index, double seconds,
                                const render::Volume& volume, std::vector<gpu::StageTime>& stages) {
  reference::TraceSettings trace;
  trace.width = frame.width;
  trace.height = frame.height;
  trace.seed = scene_.render.seed + uint32_t(index) + options_.pathTraceSeedOffset;
  trace.maxOrders = options_.pathTraceOrders;
  if (scene_.ambient) {
    if (const auto* c = std::get_if<scene::AmbientColor>(&*scene_.ambient)) trace.environment = {c->color};
    if (const auto* sh = std::get_if<scene::AmbientSh>(&*scene_.ambient))
      trace.environment = sh->coefficients;
  }
  std::vector<scene::Light> traced = view.lights;
  if (!options_.shadows)
    for (scene::Light& light : traced) light.shadows = false;
  if (obstacles_) obstacles_->update(seconds);
  tracer_.beginImage(volume, scene_.smoke, view.camera,
                     render::fullFrame(view.camera, trace.width, trace.height), traced, trace,
                     obstacles_.get());
  tracer_.accumulate(options_.pathTraceSamples);
  stages.push_back({"path trace", tracer_.traceMilliseconds()});
  // Black background, so premultiplied; opaque obstacles.
  const io::Image smoke = tracer_.image();
  for (size_t i = 0, n = size_t(smoke.width) * smoke.height; i < n; ++i) {
    const float alpha = smoke.pixels[i * 4 + 3];
    for (int c = 0; c < 4; ++c)
      frame.pixels[i * 4 + c] = smoke.pixels[i * 4 + c] + (1.0f - alpha) * frame.pixels[i * 4 + c];
  }
}

}  // namespace sixway::modes
