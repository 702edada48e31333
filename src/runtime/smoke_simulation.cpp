#include <sixway/smoke_simulation.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "runtime/internal.h"
#include "runtime/placement.h"
#include "runtime/smoke_simulation_impl.h"
#include "scene/fluid_physics.h"
#include "sim/sim_params.h"

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
  engineObstacles.clear();
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

namespace {

// The domain as the scene file it stands for, read by the scene parser: the same defaults and checks.
std::string domainScene(const SmokeDomain& d) {
  const auto vec = [](glm::vec3 v) { return nlohmann::json::array({v.x, v.y, v.z}); };
  const glm::vec3 size = glm::vec3(d.cells) * d.cellSize;
  const glm::vec3 centre = d.origin + 0.5f * size;
  nlohmann::json scene = {
      {"name", "smoke domain"},
      {"grid",
       {{"size", {d.cells.x, d.cells.y, d.cells.z}}, {"cell_size", d.cellSize}, {"origin", vec(d.origin)}}},
      {"time", {{"frame_dt", d.frameSeconds}}},
      {"fluid", {{"viscosity", d.viscosity}, {"buoyancy", {{"temperature", d.buoyancy}}}}},
      {"smoke",
       {{"extinction", d.extinction},
        {"albedo", d.albedo},
        {"phase_g", d.phaseG},
        {"dissipation", d.dissipation}}},
      // In front of the domain, far enough back for a 40° view to hold its height.
      {"camera",
       {{"position", vec(centre + glm::vec3(0.0f, 0.0f, 0.5f * size.z + 1.5f * size.y))},
        {"target", vec(centre)}}},
      {"render", {{"lightmap_size", d.lightmapSize}}}};
  return scene.dump();
}

}  // namespace

SmokeSimulation::SmokeSimulation(Device& device, const SmokeDomain& domain)
    : SmokeSimulation(device, SceneText{domainScene(domain), ".", "smoke domain"}) {}

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
  return impl_->volumes->simulation().scene().obstacles.size();
}

size_t SmokeSimulation::maxObstacles() const {
  return sim::kMaxObstacles;
}

namespace {

bool finite(glm::vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// An engine's mesh as sixway keeps it; std::invalid_argument (naming `which`) for one without triangles, with
// an index out of range or a vertex that is not finite.
std::shared_ptr<const io::Mesh> meshOf(const Obstacle& o, const std::string& which) {
  if (o.indices.empty() || o.indices.size() % 3 != 0)
    throw std::invalid_argument(which + "a mesh needs triangles: three indices each, got " +
                                std::to_string(o.indices.size()));
  auto mesh = std::make_shared<io::Mesh>();
  mesh->positions.assign(o.vertices.begin(), o.vertices.end());
  mesh->boundsMin = glm::vec3(std::numeric_limits<float>::max());
  mesh->boundsMax = glm::vec3(std::numeric_limits<float>::lowest());
  for (const glm::vec3& v : mesh->positions) {
    if (!finite(v)) throw std::invalid_argument(which + "a mesh vertex is not finite");
    mesh->boundsMin = glm::min(mesh->boundsMin, v);
    mesh->boundsMax = glm::max(mesh->boundsMax, v);
  }
  for (size_t t = 0; t < o.indices.size(); t += 3) {
    const glm::uvec3 triangle(o.indices[t], o.indices[t + 1], o.indices[t + 2]);
    if (glm::any(glm::greaterThanEqual(triangle, glm::uvec3(uint32_t(o.vertices.size())))))
      throw std::invalid_argument(which + "a mesh index is out of range (" +
                                  std::to_string(o.vertices.size()) + " vertices)");
    mesh->triangles.push_back(triangle);
  }
  return mesh;
}

// The engine's obstacle in the scene, at rest at its position (a mesh's triangles in `mesh`);
// std::invalid_argument naming what is wrong.
scene::Obstacle sceneObstacle(const Obstacle& o, const std::shared_ptr<const io::Mesh>& mesh,
                              const glm::mat4& placement, size_t index) {
  const std::string which = "obstacle " + std::to_string(index) + ": ";
  if (!finite(o.position)) throw std::invalid_argument(which + "position is not finite");
  const glm::vec3 centre = runtime::scenePoint(placement, o.position);
  scene::Obstacle result;
  result.shadows = o.shadows;
  const auto positive = [&](float value, const char* name) {
    if (!(value > 0.0f && std::isfinite(value)))
      throw std::invalid_argument(which + name + " " + std::to_string(value) + "; needs a finite value > 0");
  };
  switch (o.shape) {
    case Obstacle::Shape::Sphere:
      positive(o.radius, "radius");
      result.shape = scene::SphereObstacle{centre, o.radius};
      break;
    case Obstacle::Shape::Box:
      for (int a = 0; a < 3; ++a) positive(o.size[a], "size");
      result.shape = scene::BoxObstacle{centre, o.size};
      break;
    case Obstacle::Shape::Capsule: {
      positive(o.radius, "radius");
      positive(o.height, "height");
      if (o.height < 2.0f * o.radius)
        throw std::invalid_argument(which + "a capsule's height " + std::to_string(o.height) +
                                    " is less than its diameter " + std::to_string(2.0f * o.radius));
      if (!finite(o.axis) || glm::length(o.axis) == 0.0f)
        throw std::invalid_argument(which + "a capsule needs a finite axis that is not 0");
      result.shape = scene::CapsuleObstacle{centre, o.radius, o.height,
                                            glm::normalize(runtime::sceneDirection(placement, o.axis))};
      break;
    }
    case Obstacle::Shape::Mesh: {
      positive(o.scale, "scale");
      // A rotation: orthonormal with determinant 1, to float rounding.
      const glm::mat3 error = glm::transpose(o.rotation) * o.rotation - glm::mat3(1.0f);
      float worst = std::abs(glm::determinant(o.rotation) - 1.0f);
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) worst = std::max(worst, std::abs(error[c][r]));
      if (!(worst < 1e-4f)) throw std::invalid_argument(which + "a mesh's rotation is not a rotation");
      scene::MeshObstacle m;
      m.scale = o.scale;
      m.translate = centre;
      m.data = mesh;
      m.rotation = glm::mat3(glm::inverse(placement)) * o.rotation;
      result.shape = std::move(m);
      break;
    }
    default:
      throw std::invalid_argument(which + "unknown shape");
  }
  return result;
}

// Whether `o` is `last` but for its position (a mesh: the same triangles, compared by value).
bool sameShape(const Obstacle& o, const Obstacle& l, const io::Mesh* lastMesh) {
  if (o.shape != l.shape || o.shadows != l.shadows) return false;
  switch (o.shape) {
    case Obstacle::Shape::Sphere:
      return o.radius == l.radius;
    case Obstacle::Shape::Box:
      return o.size == l.size;
    case Obstacle::Shape::Capsule:
      return o.radius == l.radius && o.height == l.height && o.axis == l.axis;
    case Obstacle::Shape::Mesh: {
      if (o.rotation != l.rotation || o.scale != l.scale || !lastMesh ||
          o.vertices.size() != lastMesh->positions.size() ||
          o.indices.size() != 3 * lastMesh->triangles.size())
        return false;
      if (!std::equal(o.vertices.begin(), o.vertices.end(), lastMesh->positions.begin())) return false;
      for (size_t t = 0; t < lastMesh->triangles.size(); ++t)
        for (int k = 0; k < 3; ++k)
          if (o.indices[3 * t + k] != lastMesh->triangles[t][k]) return false;
      return true;
    }
  }
  return false;
}

}  // namespace

void SmokeSimulation::setObstacles(const std::vector<Obstacle>& obstacles, double seconds) {
  if (obstacles.size() > maxObstacles())
    throw std::invalid_argument("SmokeSimulation::setObstacles: " + std::to_string(obstacles.size()) +
                                " obstacles; at most " + std::to_string(maxObstacles()));
  if (!(seconds >= 0.0) || !std::isfinite(seconds))
    throw std::invalid_argument("SmokeSimulation::setObstacles: time " + std::to_string(seconds) +
                                " s; needs a finite time >= 0");
  sim::Simulation& simulation = impl_->volumes->simulation();
  const auto& last = impl_->engineObstacles;
  std::vector<Impl::EngineObstacle> kept;
  std::vector<scene::Obstacle> shapes;
  std::vector<bool> steered;
  for (size_t i = 0; i < obstacles.size(); ++i) {
    const Obstacle& o = obstacles[i];
    if (!finite(o.position))
      throw std::invalid_argument("obstacle " + std::to_string(i) + ": position is not finite");
    steered.push_back(i < last.size() && impl_->obstaclesPlacement == impl_->placement &&
                      sameShape(o, last[i].obstacle, last[i].mesh.get()));
    Impl::EngineObstacle record{o, steered.back() ? last[i].mesh : nullptr};
    record.obstacle.vertices = {};
    record.obstacle.indices = {};
    if (steered.back()) {  // where it is, on its way: steered below
      shapes.push_back(simulation.scene().obstacles[i]);
      shapes.back().motion = simulation.obstacleMotion(i);
    } else {
      const std::string which = "obstacle " + std::to_string(i) + ": ";
      if (o.shape == Obstacle::Shape::Mesh) record.mesh = meshOf(o, which);
      shapes.push_back(sceneObstacle(o, record.mesh, impl_->placement, i));
    }
    kept.push_back(std::move(record));
  }
  const bool changed = last.size() != obstacles.size() || simulation.obstacleSetsMade() == 0 ||
                       std::find(steered.begin(), steered.end(), false) != steered.end();
  if (changed) simulation.setObstacles(shapes);
  // One given where it was last time is on its way there already (or rests there: steering it again would
  // move it by rounding and make the lattice mark its cells again each step).
  for (size_t i = 0; i < obstacles.size(); ++i)
    if (steered[i] && obstacles[i].position != last[i].obstacle.position)
      simulation.steerObstacle(i, runtime::scenePoint(impl_->placement, obstacles[i].position), seconds);
  impl_->engineObstacles = std::move(kept);
  impl_->obstaclesPlacement = impl_->placement;
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
