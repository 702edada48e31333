#include <sixway/smoke_simulation.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "runtime/internal.h"
#include "runtime/placement.h"
#include "runtime/smoke_simulation_impl.h"
#include "scene/fluid_physics.h"

namespace sixway {

SmokeSimulation::Impl::Impl(const gpu::Context& context, const gpu::PipelineCache& cache, scene::Scene scene)
    : context(context), cache(cache), scene(std::move(scene)) {
  start();
  maxStepsPerRecord =
      std::min(2 * uint32_t(scene::lbmStepsPerFrame(this->scene)), volumes->simulation().stepCapacity());
}

void SmokeSimulation::Impl::start() {
  volumes.reset();
  volumes =
      std::make_unique<runtime::SimulatedVolumes>(context, cache, scene, std::numeric_limits<int>::max());
  frames = 0;
  advanced = false;
  carried = 0.0;
  ++starts;
}

namespace {

// The runtime simulates; a scene that plays VDB files back is refused naming its file.
scene::Scene simulated(scene::Scene scene, const std::string& source) {
  scene::requireSimulated(scene, source);
  return scene;
}

}  // namespace

SmokeSimulation::SmokeSimulation(Device& device, const std::filesystem::path& scene)
    : impl_(std::make_unique<Impl>(runtime::Access::context(device), runtime::Access::pipelineCache(device),
                                   simulated(scene::loadScene(scene), scene.string()))) {}

SmokeSimulation::SmokeSimulation(Device& device, const SceneText& scene)
    : impl_(std::make_unique<Impl>(
          runtime::Access::context(device), runtime::Access::pipelineCache(device),
          simulated(scene::parseSceneText(scene.json, scene.name, scene.directory), scene.name))) {}

SmokeSimulation::~SmokeSimulation() = default;

void SmokeSimulation::advance() {
  impl_->volumes->volume(impl_->frames);
  ++impl_->frames;
  impl_->advanced = true;
}

void SmokeSimulation::record(VkCommandBuffer commands, uint64_t frame) {
  impl_->volumes->recordFrame(commands, frame);
  ++impl_->frames;
}

uint32_t SmokeSimulation::record(VkCommandBuffer commands, uint64_t frame, double seconds) {
  if (!(seconds >= 0.0) || !std::isfinite(seconds))
    throw std::invalid_argument("SmokeSimulation::record: frame time " + std::to_string(seconds) +
                                " s; needs a finite time >= 0");
  const double step = stepSeconds();
  // A whole step that rounding leaves a hair short still counts: the step is a float (relative error 6e-8),
  // so a frame of n steps can read n − 1e-6; within 1e-4 of a step is taken as the whole.
  const double available = std::floor((impl_->carried + seconds) / step + 1e-4);
  const uint32_t steps = uint32_t(std::min(available, double(impl_->maxStepsPerRecord)));
  impl_->carried = available > double(steps) ? 0.0 : std::max(0.0, impl_->carried + seconds - steps * step);
  if (steps == 0) return 0;
  impl_->volumes->recordFrame(commands, frame, steps);
  // The scene's frames in the simulated time (what its camera and light paths and the guide's jitter follow),
  // not the engine's records.
  impl_->frames = int(std::floor(impl_->volumes->simulation().seconds() / impl_->scene.time.frameDt + 1e-4));
  return steps;
}

double SmokeSimulation::stepSeconds() const {
  return impl_->volumes->simulation().units().stepSeconds;
}

void SmokeSimulation::setMaxStepsPerRecord(uint32_t steps) {
  if (steps == 0 || steps > stepCapacity())
    throw std::invalid_argument("SmokeSimulation::setMaxStepsPerRecord: " + std::to_string(steps) +
                                "; 1 to " + std::to_string(stepCapacity()));
  impl_->maxStepsPerRecord = steps;
}

uint32_t SmokeSimulation::maxStepsPerRecord() const {
  return impl_->maxStepsPerRecord;
}

uint32_t SmokeSimulation::stepCapacity() const {
  return impl_->volumes->simulation().stepCapacity();
}

void SmokeSimulation::restart() {
  impl_->start();
}

SmokeVolume SmokeSimulation::volume() const {
  const render::Volume v = impl_->volumes->currentVolume();
  return {v.density->handle(), v.temperature ? v.temperature->handle() : VK_NULL_HANDLE, v.grid.size,
          v.grid.origin, v.grid.cellSize};
}

int SmokeSimulation::framesSimulated() const {
  return impl_->frames;
}

double SmokeSimulation::seconds() const {
  return impl_->volumes->simulation().seconds();
}

std::vector<StageTime> SmokeSimulation::stageTimes() const {
  // advance()'s own frame, or on the engine path the latest recorded frame whose measurements are in.
  const sim::Simulation& simulation = impl_->volumes->simulation();
  if (!impl_->advanced && simulation.framesReported() == 0) return {};
  const sim::StepTimes& t = impl_->advanced ? impl_->volumes->frameTimes() : simulation.report().times;
  return {{"sim/obstacles", t.obstacles},
          {"sim/lbm", t.lbm},
          {"sim/smoke", t.smoke},
          {"sim/forces+watchdog", t.forces + t.watchdog}};
}

size_t SmokeSimulation::obstacleCount() const {
  return impl_->scene.obstacles.size();
}

void SmokeSimulation::setPlacement(const glm::mat4& worldFromScene) {
  impl_->placement = runtime::uprightPlacement(worldFromScene);
}

glm::mat4 SmokeSimulation::placement() const {
  return impl_->placement;
}

glm::vec3 SmokeSimulation::obstaclePosition(size_t obstacle) const {
  if (obstacle >= obstacleCount())
    throw std::invalid_argument("SmokeSimulation::obstaclePosition: no obstacle " + std::to_string(obstacle));
  const sim::Simulation& simulation = impl_->volumes->simulation();
  return runtime::worldPoint(impl_->placement,
                             simulation.obstacles().positionAt(obstacle, simulation.seconds()));
}

void SmokeSimulation::steerObstacle(size_t obstacle, glm::vec3 target) {
  if (obstacle >= obstacleCount())
    throw std::invalid_argument("SmokeSimulation::steerObstacle: no obstacle " + std::to_string(obstacle));
  impl_->volumes->simulation().steerObstacle(obstacle, runtime::scenePoint(impl_->placement, target));
}

void SmokeSimulation::steerObstacle(size_t obstacle, glm::vec3 target, double seconds) {
  if (obstacle >= obstacleCount())
    throw std::invalid_argument("SmokeSimulation::steerObstacle: no obstacle " + std::to_string(obstacle));
  impl_->volumes->simulation().steerObstacle(obstacle, runtime::scenePoint(impl_->placement, target),
                                             seconds);
}

float SmokeSimulation::maxObstacleSpeed() const {
  return float(impl_->volumes->simulation().obstacleSpeedLimit());
}

void SmokeSimulation::setEmitters(const std::vector<Emitter>& emitters) {
  std::vector<sim::Emitter> scene;
  for (const Emitter& e : emitters)
    scene.push_back({runtime::scenePoint(impl_->placement, e.position), e.radius,
                     runtime::sceneDirection(impl_->placement, e.velocity), e.densityRate, e.temperatureRate,
                     e.on});
  try {
    impl_->volumes->simulation().setEmitters(scene);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("SmokeSimulation::setEmitters: ") + e.what());
  }
}

size_t SmokeSimulation::maxEmitters() const {
  return sim::kMaxInlets;
}

float SmokeSimulation::maxEmitterSpeed() const {
  return float(impl_->volumes->simulation().emitterSpeedLimit());
}

void SmokeSimulation::setInletStrength(float strength) {
  impl_->volumes->simulation().setInletStrength(strength);
}

float SmokeSimulation::inletStrength() const {
  return impl_->volumes->simulation().inletStrength();
}

float SmokeSimulation::maxInletStrength() const {
  return impl_->volumes->simulation().maxInletStrength();
}

}  // namespace sixway
