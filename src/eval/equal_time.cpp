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
namespace {

// The largest power of two ≤ min(16, spp): whole passes, few submits.
uint32_t passOf(uint32_t spp) {
  uint32_t p = 1;
  while (p * 2 <= std::min(16u, spp)) p *= 2;
  return p;
}

reference::TraceSettings traceSettings(const scene::Scene& scene, int orders) {
  reference::TraceSettings settings;
  settings.width = scene.render.width;
  settings.height = scene.render.height;
  settings.maxOrders = orders;
  settings.background = scene.render.background;
  if (scene.ambient) {
    if (const auto* c = std::get_if<scene::AmbientColor>(&*scene.ambient)) settings.environment = {c->color};
    if (const auto* sh = std::get_if<scene::AmbientSh>(&*scene.ambient))
      settings.environment = sh->coefficients;
  }
  return settings;
}

// The path tracer on one frame of the scene (camera, lights and obstacles at the frame's time).
class FrameTracer {
 public:
  FrameTracer(const gpu::Context& context, const gpu::PipelineCache& cache, const scene::Scene& scene,
              int index, const render::Volume& volume, int orders)
      : scene_(scene),
        index_(index),
        volume_(volume),
        camera_(render::sceneCamera(scene.camera, index)),
        lights_(render::sceneLights(scene.lights, index)),
        frame_(render::fullFrame(camera_, scene.render.width, scene.render.height)),
        settings_(traceSettings(scene, orders)),
        tracer_(context, cache) {
    if (!scene.obstacles.empty()) {
      obstacles_ = std::make_unique<render::ObstacleBvh>(context, scene.obstacles);
      obstacles_->update(runtime::SimulatedVolumes::frameSeconds(scene, index));
    }
  }

  // A render of `spp` samples in passes of `perPass` with its own random numbers; its image and its time on
  // the host's clock around the submissions (see equal_time.h on why not GPU timestamps).
  std::pair<io::Image, double> trace(uint32_t spp, uint32_t perPass, uint32_t seedOffset) {
    settings_.samplesPerPass = int(perPass);
    settings_.seed = scene_.render.seed + uint32_t(index_) + seedOffset;
    // One untimed pass first: lavapipe compiles the tracer again for each samples-per-pass value (it
    // specializes on the uniform block, render/gpu_layout.h), which is not the tracer's time.
    tracer_.beginImage(volume_, scene_.smoke, camera_, frame_, lights_, settings_, obstacles_.get());
    tracer_.accumulate(perPass);
    tracer_.beginImage(volume_, scene_.smoke, camera_, frame_, lights_, settings_, obstacles_.get());
    const auto started = std::chrono::steady_clock::now();
    tracer_.accumulate(spp);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
    return std::pair(tracer_.image(), ms);
  }

 private:
  const scene::Scene& scene_;
  const int index_;
  const render::Volume& volume_;
  const render::Camera camera_;
  const std::vector<scene::Light> lights_;
  const render::ImagePlane frame_;
  reference::TraceSettings settings_;
  reference::PathTracer tracer_;
  std::unique_ptr<render::ObstacleBvh> obstacles_;
};

// Time against samples: renders of 1, 2, 4, ... spp.
struct TimeCurve {
  std::vector<std::pair<uint32_t, double>> times;  // (spp, ms)
  std::vector<io::Image> images;
};

// Until a render takes longer than the budget, and at least up to 16 spp, so the curve shows how the noise
// falls even where one sample already costs more than the budget.
TimeCurve timeCurve(FrameTracer& tracer, double budgetMs) {
  constexpr uint32_t kCurveSamples = 16;
  TimeCurve curve;
  for (uint32_t spp = 1; spp <= (1u << 16); spp *= 2) {
    auto [image, ms] = tracer.trace(spp, passOf(spp), spp);
    curve.times.emplace_back(spp, ms);
    curve.images.push_back(std::move(image));
    if (ms > budgetMs && spp >= kCurveSamples) break;
  }
  return curve;
}

// The sample count at the budget, linear in time between the two renders around it (at least one), in whole
// passes.
uint32_t samplesAtBudget(const TimeCurve& curve, double budgetMs) {
  double equal = 1;
  for (size_t k = 1; k < curve.times.size(); ++k) {
    const auto [s0, t0] = curve.times[k - 1];
    const auto [s1, t1] = curve.times[k];
    if (t1 >= budgetMs) {
      equal = t1 > t0 ? double(s0) + (budgetMs - t0) * double(s1 - s0) / (t1 - t0) : double(s0);
      break;
    }
  }
  uint32_t spp = uint32_t(std::max(1.0, std::floor(equal)));
  return spp - spp % passOf(spp);
}

nlohmann::json curveJson(const TimeCurve& curve, const io::Image& truth) {
  nlohmann::json json = nlohmann::json::array();
  for (size_t k = 0; k < curve.times.size(); ++k) {
    nlohmann::json point = metrics::compareImages(curve.images[k], truth).json();
    point["spp"] = curve.times[k].first;
    point["ms"] = curve.times[k].second;
    json.push_back(point);
  }
  return json;
}

}  // namespace

nlohmann::json equalTimeStudy(const gpu::Context& context, const gpu::PipelineCache& cache,
                              const scene::Scene& scene, int index, const render::Volume& volume,
                              const EqualTimeSettings& study, const io::Image* neural) {
  const double budgetMs = study.budgetMs;
  FrameTracer tracer(context, cache, scene, index, volume, study.orders);
  const TimeCurve curve = timeCurve(tracer, budgetMs);
  const uint32_t equalSpp = samplesAtBudget(curve, budgetMs);
  auto [equalImage, equalMs] = tracer.trace(equalSpp, passOf(equalSpp), 0x51ed27u);
  // The stand-in for the noise-free image: 16 times the equal-time samples or more, with random numbers of
  // its own (a shared seed would make the short renders prefixes of it and hide their noise).
  const uint32_t referenceSpp = std::max(study.samples, (16 * equalSpp + 63) / 64 * 64);
  const io::Image truth = tracer.trace(referenceSpp, 64, 0x9e3779b9u).first;
  nlohmann::json result = {{"budget_ms", budgetMs},
                           {"reference_spp", referenceSpp},
                           {"curve", curveJson(curve, truth)},
                           {"equal_time_spp", equalSpp},
                           {"equal_time_ms", equalMs},
                           {"equal_time", metrics::compareImages(equalImage, truth).json()}};
  if (neural) result["neural"] = metrics::compareImages(*neural, truth).json();
  return result;
}

}  // namespace sixway::eval
