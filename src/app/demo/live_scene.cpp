#include "app/demo/live_scene.h"

#include <algorithm>

#include "modes/scene_source.h"
#include "render/scene_frame.h"
#include "runtime/internal.h"
#include "runtime/scene_lights.h"
#include "runtime/scene_volumes.h"

namespace sixway::app::demo {
std::vector<scene::Light> startingLights(const scene::Scene& scene) {
  std::vector<scene::Light> lights = render::sceneLights(scene.lights, 0);
  for (scene::Light& l : lights) l.path.reset();
  if (lights.size() > kMaxDemoLights) lights.resize(kMaxDemoLights);
  return lights;
}

LiveScene::LiveScene(gpu::Context& context, gpu::PipelineCache& cache, const std::filesystem::path& scene,
                     const LiveSceneOptions& options)
    : device_(runtime::Access::borrowDevice(context, cache)), options_(options) {
  playedScene_ = scene::loadScene(scene);
  if (playedScene_.vdb) {
    playback_ = modes::openSceneVolumes(context, cache, playedScene_, scene::sceneFrameCount(playedScene_),
                                        scene.string());
    return;
  }
  simulation_ = std::make_unique<SmokeSimulation>(device_, scene);
  simulation_->advance();  // frame 0
}

const scene::Scene& LiveScene::scene() const {
  return simulation_ ? runtime::Access::scene(*simulation_) : playedScene_;
}

double LiveScene::seconds() const {
  return runtime::SimulatedVolumes::frameSeconds(scene(), frame());
}

void LiveScene::advance() {
  if (!simulation_) {
    playedFrame_ = (playedFrame_ + 1) % playback_->frameCount();
    return;
  }
  simulation_->advance();
}

void LiveScene::reset() {
  if (!simulation_) {
    playedFrame_ = 0;
    return;
  }
  simulation_->restart();
  followObstacles();
  simulation_->advance();
}

void LiveScene::steerObstacle(size_t obstacle, glm::vec3 target) {
  if (!simulation_) return;  // a played-back scene has no obstacles
  simulation_->steerObstacle(obstacle, target);
  followObstacles();
}

void LiveScene::followObstacles() {
  if (!simulation_) return;
  const sim::Simulation& simulation = runtime::Access::volumes(*simulation_).simulation();
  for (auto& [key, renderer] : modeRenderers_)
    for (size_t i = 0; i < obstacleCount(); ++i) renderer->setObstacleMotion(i, simulation.obstacleMotion(i));
}

void LiveScene::setInletStrength(float strength) {
  if (!simulation_) return;
  simulation_->setInletStrength(std::clamp(strength, 0.0f, simulation_->maxInletStrength()));
}

std::vector<gpu::StageTime> LiveScene::simulationTimes() const {
  std::vector<gpu::StageTime> times;
  if (!simulation_) return times;
  for (const StageTime& t : simulation_->stageTimes()) times.push_back({t.name, t.milliseconds});
  return times;
}

modes::ModeRenderer& LiveScene::modeRendererFor(modes::RenderMode mode, bool shadows) {
  auto& slot = modeRenderers_[{mode, shadows}];
  if (!slot) {
    modes::ModeOptions options;
    options.mode = mode;
    options.weights = options_.weights;
    options.fp16 = options_.fp16;
    options.shadows = shadows;
    options.shadowTiles = kMaxDemoLights;
    options.download = false;
    try {
      slot = std::make_unique<modes::ModeRenderer>(runtime::Access::context(device_),
                                                   runtime::Access::pipelineCache(device_), scene(), options);
    } catch (...) {
      modeRenderers_.erase({mode, shadows});
      throw;
    }
    followObstacles();
  }
  return *slot;
}

LiveFrame LiveScene::renderNeural(const Camera& camera, const std::vector<scene::Light>& lights,
                                  bool shadows) {
  auto& slot = renderers_[shadows];
  if (!slot) {
    RendererOptions options;
    options.weights = options_.weights;
    options.fp16 = options_.fp16;
    options.shadows = shadows;
    options.shadowedLights = kMaxDemoLights;
    try {
      slot = std::make_unique<SmokeRenderer>(device_, *simulation_, options);
    } catch (...) {
      renderers_.erase(shadows);
      throw;
    }
  }
  SmokeRenderer& renderer = *slot;
  renderer.setCamera(camera);
  std::vector<Light> converted;
  for (const scene::Light& l : lights) converted.push_back(runtime::publicLight(l));
  renderer.setLights(converted);
  renderer.render();
  const runtime::RealtimeFrame& f = runtime::Access::frame(renderer);
  LiveFrame out{&f.color(), &f.guide(), &f.lightmaps().a, &f.lightmaps().b, {}};
  for (const StageTime& t : renderer.stageTimes()) out.stages.push_back({t.name, t.milliseconds});
  return out;
}

LiveFrame LiveScene::render(modes::RenderMode mode, const Camera& camera,
                            const std::vector<scene::Light>& lights, bool shadows) {
  if (mode == modes::RenderMode::Neural && simulation_) return renderNeural(camera, lights, shadows);
  modes::ModeRenderer& renderer = modeRendererFor(mode, shadows);
  const runtime::FrameView view{
      render::Camera::lookAt(camera.position, camera.target, camera.up, camera.fovYDegrees), lights};
  modes::RenderedFrame r = renderer.render(
      view, frame(), seconds(),
      simulation_ ? runtime::Access::volumes(*simulation_).currentVolume() : playback_->volume(frame()));
  return {&renderer.colorImage(), &renderer.guideImage(), &renderer.lightmapImageA(),
          &renderer.lightmapImageB(), std::move(r.stages)};
}

}  // namespace sixway::app::demo
