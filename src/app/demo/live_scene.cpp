#include "app/demo/live_scene.h"

#include <algorithm>
#include <climits>

#include "render/scene_frame.h"

namespace sixway::app::demo {

std::vector<io::Light> startingLights(const io::Scene& scene) {
  std::vector<io::Light> lights = render::sceneLights(scene.lights, 0);
  for (io::Light& l : lights) l.path.reset();
  if (lights.size() > kMaxDemoLights) lights.resize(kMaxDemoLights);
  return lights;
}

LiveScene::LiveScene(const gpu::Context& context, const gpu::PipelineCache& cache, const io::Scene& scene,
                     const LiveSceneOptions& options)
    : context_(context), cache_(cache), scene_(scene), options_(options) {
  reset();
}

void LiveScene::reset() {
  volumes_.reset();  // one simulation's memory at a time
  volumes_ = std::make_unique<runtime::SimulatedVolumes>(context_, cache_, scene_, INT_MAX);
  for (auto& [key, pipeline] : pipelines_)
    for (size_t i = 0; i < scene_.obstacles.size(); ++i)
      pipeline->setObstacleMotion(i, scene_.obstacles[i].motion);
  frame_ = 0;
  volumes_->volume(frame_);
}

void LiveScene::advance() {
  ++frame_;
  volumes_->volume(frame_);
}

glm::vec3 LiveScene::obstaclePosition(size_t obstacle) const {
  return volumes_->simulation().obstacles().positionAt(obstacle, volumes_->simulation().seconds());
}

void LiveScene::steerObstacle(size_t obstacle, glm::vec3 target) {
  sim::Simulation& simulation = volumes_->simulation();
  simulation.steerObstacle(obstacle, target);
  for (auto& [key, pipeline] : pipelines_)
    pipeline->setObstacleMotion(obstacle, simulation.obstacleMotion(obstacle));
}

void LiveScene::setInletStrength(float strength) {
  sim::Simulation& simulation = volumes_->simulation();
  simulation.setInletStrength(std::clamp(strength, 0.0f, simulation.maxInletStrength()));
}

eval::FramePipeline& LiveScene::pipelineFor(eval::RenderMode mode, bool shadows) {
  auto& slot = pipelines_[{mode, shadows}];
  if (!slot) {
    eval::FramePipelineOptions options;
    options.mode = mode;
    options.weights = options_.weights;
    options.fp16 = options_.fp16;
    options.shadows = shadows;
    options.shadowTiles = kMaxDemoLights;
    options.download = false;
    try {
      slot = std::make_unique<eval::FramePipeline>(context_, cache_, scene_, options);
    } catch (...) {
      pipelines_.erase({mode, shadows});
      throw;
    }
    const sim::Simulation& simulation = volumes_->simulation();
    for (size_t i = 0; i < scene_.obstacles.size(); ++i)
      slot->setObstacleMotion(i, simulation.obstacleMotion(i));
  }
  return *slot;
}

eval::RenderedFrame LiveScene::render(eval::RenderMode mode, const eval::FrameView& view, bool shadows) {
  eval::FramePipeline& pipeline = pipelineFor(mode, shadows);
  const render::Volume volume = volumes_->volume(frame_);
  return pipeline.render(view, frame_, seconds(), volume);
}

const eval::FramePipeline& LiveScene::pipeline(eval::RenderMode mode, bool shadows) {
  return pipelineFor(mode, shadows);
}

}  // namespace sixway::app::demo
