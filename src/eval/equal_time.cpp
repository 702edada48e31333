#include "eval/equal_time.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <variant>

#include "metrics/image_metrics.h"
#include "reference/path_tracer.h"
#include "render/camera.h"
#include "render/obstacle_bvh.h"
#include "render/scene_frame.h"
#include "runtime/scene_volumes.h"

namespace sixway::eval {

nlohmann::json equalTimeStudy(const gpu::Context& context, const gpu::PipelineCache& cache,
                              const scene::Scene& scene, int index, const render::Volume& volume,
                              const EqualTimeSettings& study, const io::Image* neural) {
  const double budgetMs = study.budgetMs;
  const render::Camera camera = render::sceneCamera(scene.camera, index);
  const std::vector<scene::Light> lights = render::sceneLights(scene.lights, index);
  const render::ImagePlane frame = render::fullFrame(camera, scene.render.width, scene.render.height);
  reference::TraceSettings settings;
  settings.width = scene.render.width;
  settings.height = scene.render.height;
  settings.maxOrders = study.orders;
  settings.background = scene.render.background;
  if (scene.ambient) {
    if (const auto* c = std::get_if<scene::AmbientColor>(&*scene.ambient)) settings.environment = {c->color};
    if (const auto* sh = std::get_if<scene::AmbientSh>(&*scene.ambient))
      settings.environment = sh->coefficients;
  }
  reference::PathTracer tracer(context, cache);
  std::unique_ptr<render::ObstacleBvh> obstacles;
  if (!scene.obstacles.empty()) {
    obstacles = std::make_unique<render::ObstacleBvh>(context, scene.obstacles);
    obstacles->update(runtime::SimulatedVolumes::frameSeconds(scene, index));
  }
  // A render of `spp` samples in passes of `perPass` with its own random numbers; its image and its time on
  // the host's clock around the submissions (see equal_time.h on why not GPU timestamps).
  const auto trace = [&](uint32_t spp, uint32_t perPass, uint32_t seedOffset) {
    settings.samplesPerPass = int(perPass);
    settings.seed = scene.render.seed + uint32_t(index) + seedOffset;
    // One untimed pass first: lavapipe compiles the tracer again for each samples-per-pass value (it
    // specializes on the uniform block, render/gpu_layout.h), which is not the tracer's time.
    tracer.beginImage(volume, scene.smoke, camera, frame, lights, settings, obstacles.get());
    tracer.accumulate(perPass);
    tracer.beginImage(volume, scene.smoke, camera, frame, lights, settings, obstacles.get());
    const auto started = std::chrono::steady_clock::now();
    tracer.accumulate(spp);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
    return std::pair(tracer.image(), ms);
  };
  const auto passOf =
      [](uint32_t spp) {  // the largest power of two ≤ min(16, spp): whole passes, few submits
        uint32_t p = 1;
        while (p * 2 <= std::min(16u, spp)) p *= 2;
        return p;
      };

  // Time against samples: 1, 2, 4, ... spp, until a render takes longer than the budget, and at least up to
  // 16 spp, so the curve shows how the noise falls even where one sample already costs more than the budget.
  constexpr uint32_t kCurveSamples = 16;
  std::vector<std::pair<uint32_t, double>> times;  // (spp, ms)
  std::vector<io::Image> images;
  for (uint32_t spp = 1; spp <= (1u << 16); spp *= 2) {
    auto [image, ms] = trace(spp, passOf(spp), spp);
    times.emplace_back(spp, ms);
    images.push_back(std::move(image));
    if (ms > budgetMs && spp >= kCurveSamples) break;
  }
  // The sample count at the budget, linear in time between the two renders around it (at least one).
  double equal = 1;
  for (size_t k = 1; k < times.size(); ++k) {
    const auto [s0, t0] = times[k - 1];
    const auto [s1, t1] = times[k];
    if (t1 >= budgetMs) {
      equal = t1 > t0 ? double(s0) + (budgetMs - t0) * double(s1 - s0) / (t1 - t0) : double(s0);
      break;
    }
  }
  uint32_t equalSpp = uint32_t(std::max(1.0, std::floor(equal)));
  equalSpp -= equalSpp % passOf(equalSpp);
  auto [equalImage, equalMs] = trace(equalSpp, passOf(equalSpp), 0x51ed27u);

  // The stand-in for the noise-free image: 16 times the equal-time samples or more, with random numbers of
  // its own (a shared seed would make the short renders prefixes of it and hide their noise).
  const uint32_t referenceSpp = std::max(study.samples, (16 * equalSpp + 63) / 64 * 64);
  const io::Image truth = trace(referenceSpp, 64, 0x9e3779b9u).first;

  nlohmann::json curve = nlohmann::json::array();
  for (size_t k = 0; k < times.size(); ++k) {
    nlohmann::json point = metrics::compareImages(images[k], truth).json();
    point["spp"] = times[k].first;
    point["ms"] = times[k].second;
    curve.push_back(point);
  }
  nlohmann::json result = {
      {"budget_ms", budgetMs},    {"reference_spp", referenceSpp},
      {"curve", curve},           {"equal_time_spp", equalSpp},
      {"equal_time_ms", equalMs}, {"equal_time", metrics::compareImages(equalImage, truth).json()}};
  if (neural) result["neural"] = metrics::compareImages(*neural, truth).json();
  return result;
}

}  // namespace sixway::eval
