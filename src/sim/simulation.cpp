#include "sim/simulation.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "gpu/context.h"
#include "gpu/sequence.h"
#include "sim/sim_params.h"
#include "sim/watchdog.h"

namespace sixway::sim {
namespace {

const scene::Scene& simulated(const scene::Scene& scene) {
  scene::requireSimulated(scene, scene.name);
  return scene;
}

using Box = std::pair<glm::ivec3, glm::ivec3>;

bool empty(const Box& box) {
  return glm::any(glm::greaterThanEqual(box.first, box.second));
}

// The smallest box that holds both (an empty one holds nothing).
Box cover(const Box& a, const Box& b) {
  if (empty(a)) return b;
  if (empty(b)) return a;
  return {glm::min(a.first, b.first), glm::max(a.second, b.second)};
}

}  // namespace

Simulation::Simulation(const gpu::Context& context, const gpu::PipelineCache& cache,
                       const scene::Scene& scene)
    : context_(&context), scene_(simulated(scene)), units_(latticeUnits(scene)) {
  obstacles_ = std::make_unique<ObstacleSet>(context, cache, scene, units_);
  lbm_ = std::make_unique<LbmSolver>(context, cache, lbmSettings(scene, units_));
  SmokeSettings smoke;
  smoke.lattice = scene.grid.size;
  smoke.upres = scene.grid.smokeUpres;
  smoke.faces = scene.boundaries.faces;
  smoke.decayPerStep = std::exp(-scene.smoke.dissipation * units_.stepSeconds);
  smoke.sparse = scene.smoke.sparse;
  smoke.sparseThreshold = scene.smoke.sparseThreshold;
  smoke_ = std::make_unique<SmokeTransport>(context, cache, smoke);
  speedStats_ = std::make_unique<gpu::ReduceStats>(context, cache, lbm_->cells(), gpu::ReduceInput{4, 3});
  densityStats_ = std::make_unique<gpu::ReduceStats>(context, cache, smoke_->cells(), gpu::ReduceInput{2, 1});

  // A frame at a time, and at least 64 steps per submission for long runs (each submission waits).
  capacity_ = uint32_t(std::max(units_.stepsPerFrame, 64));
  params_ = gpu::Buffer(context, uint64_t(capacity_) * sizeof(StepParams), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                        gpu::MemoryKind::FrameParameters, "step parameters");
  forces_ = gpu::Buffer::storage(context, uint64_t(capacity_) * kMaxObstacles * 16, "obstacle forces");
  flagsDispatch_ =
      gpu::Buffer(context, uint64_t(capacity_) * ObstacleSet::kFlagsDispatchStride,
                  VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, gpu::MemoryKind::FrameParameters, "flags dispatch");
  sweptCover_ = obstacles_->sweptBox();
  inletCover_ = obstacles_->inletBox();
  smoke_->upload(std::vector<glm::vec2>(smoke_->cells(), glm::vec2(0)));
  lbm_->initialize(std::vector<glm::vec4>(lbm_->cells(), glm::vec4(0, 0, 0, 1)), 0);
}

Simulation::~Simulation() = default;

void Simulation::setFlow(const std::vector<glm::vec3>& velocity, const std::vector<float>& density) {
  if (velocity.size() != lbm_->cells() || density.size() != lbm_->cells())
    throw std::invalid_argument("Simulation::setFlow: one velocity and one density per lattice cell");
  std::vector<glm::vec4> macro(velocity.size());
  for (size_t i = 0; i < macro.size(); ++i)
    macro[i] = glm::vec4(units_.toLatticeVelocity(velocity[i]), density[i]);
  lbm_->initialize(macro, int(step_ % 2));
}

double Simulation::obstacleSpeedLimit() const {
  return 0.5 * scene_.fluid.maxLatticeVelocity / units_.velocityScale;
}

void Simulation::steerObstacle(size_t obstacle, glm::vec3 target, std::optional<double> seconds) {
  if (seconds && !(*seconds >= 0.0 && std::isfinite(*seconds)))
    throw std::invalid_argument("steering time " + std::to_string(*seconds) + " s; needs a finite time >= 0");
  if (!(std::isfinite(target.x) && std::isfinite(target.y) && std::isfinite(target.z)))
    throw std::invalid_argument("steering target is not finite");
  const double now = this->seconds();
  const glm::vec3 from = obstacles_->positionAt(obstacle, now);
  const double arrival = seconds.value_or(units_.stepSeconds * units_.stepsPerFrame);
  // At least a step: a wall that jumps has no velocity for bounce-back to follow.
  const double duration = std::max(
      {arrival, double(units_.stepSeconds), double(glm::length(target - from)) / obstacleSpeedLimit()});
  scene::Motion motion;
  motion.keyframes = {{float(now), from}, {float(now + duration), target}};
  obstacles_->setMotion(obstacle, motion);
  coverBoxes();
}

void Simulation::setObstacles(std::vector<scene::Obstacle> obstacles) {
  if (std::optional<gpu::Buffer> old = obstacles_->setObstacles(obstacles)) {
    // The recorded steps read the old occupancy, which frames in flight may still do.
    retiredBuffers_.emplace_back(lastRecordedFrame_, std::move(*old));
    retireSequences();
  }
  scene_.obstacles = std::move(obstacles);
  ++obstacleSetsMade_;
  flagsSchedule_.invalidate();  // another mesh may have the same StepParams
  coverBoxes();
}

double Simulation::emitterSpeedLimit() const {
  return scene_.fluid.maxLatticeVelocity / units_.velocityScale;
}

void Simulation::setEmitters(std::span<const Emitter> emitters) {
  for (size_t i = 0; i < emitters.size(); ++i) {
    const Emitter& e = emitters[i];
    const std::string which = "emitter " + std::to_string(i) + ": ";
    if (!(e.radius >= 0.0f && std::isfinite(e.radius)))
      throw std::invalid_argument(which + "radius " + std::to_string(e.radius) +
                                  " m; needs a finite radius >= 0");
    if (!(e.densityRate >= 0.0f && e.temperatureRate >= 0.0f && std::isfinite(e.densityRate) &&
          std::isfinite(e.temperatureRate)))
      throw std::invalid_argument(which + "rates must be finite and >= 0");
    if (!(std::isfinite(e.centre.x) && std::isfinite(e.centre.y) && std::isfinite(e.centre.z)))
      throw std::invalid_argument(which + "position is not finite");
    if (!(glm::length(e.velocity) <= emitterSpeedLimit()))
      throw std::invalid_argument(which + "speed " + std::to_string(glm::length(e.velocity)) +
                                  " m/s; the lattice follows at most " + std::to_string(emitterSpeedLimit()) +
                                  " m/s (fluid.max_lattice_velocity)");
  }
  obstacles_->setEmitters(emitters);
  coverBoxes();
}

void Simulation::coverBoxes() {
  const Box swept = cover(sweptCover_, obstacles_->sweptBox());
  const Box inlets = cover(inletCover_, obstacles_->inletBox());
  if (swept == sweptCover_ && inlets == inletCover_) return;
  sweptCover_ = swept;
  inletCover_ = inlets;
  retireSequences();
}

void Simulation::retireSequences() {
  // Frames an engine has in flight may still run the old sequences.
  for (auto& [key, sequence] : sequences_) retired_.emplace_back(lastRecordedFrame_, std::move(sequence));
  sequences_.clear();
}

float Simulation::maxInletStrength() const {
  float fastest = 0.0f;
  for (const scene::Inlet& inlet : scene_.inlets)
    fastest = std::max(fastest, units_.toLatticeVelocity(glm::length(inlet.velocity)));
  if (fastest <= 0.0f) return 1.0f;
  return std::clamp(scene_.fluid.maxLatticeVelocity / fastest, 1.0f, 2.0f);
}

void Simulation::setInletStrength(float strength) {
  if (!(strength >= 0.0f && strength <= maxInletStrength()))
    throw std::invalid_argument("inlet strength " + std::to_string(strength) + " outside [0, " +
                                std::to_string(maxInletStrength()) + "]");
  inletStrength_ = strength;
  obstacles_->setInletStrength(strength);
}

gpu::Sequence& Simulation::sequenceFor(uint32_t steps, int parity) {
  auto& slot = sequences_[{steps, parity, obstacles_->obstacleCount() > 0}];
  if (slot) return *slot;
  // Stages per step: obstacles, forces, lbm, and the smoke's.
  slot = std::make_unique<gpu::Sequence>(*context_, (3 + smoke_->stagesPerStep()) * steps + 1);
  ++sequencesRecorded_;
  gpu::Sequence& sequence = *slot;
  const uint32_t obstacleCount = uint32_t(obstacles_->obstacleCount());
  if (obstacleCount > 0) sequence.fill(forces_, 0);
  for (uint32_t s = 0; s < steps; ++s) {
    const int stepParity = (parity + int(s)) % 2;  // LbmSolver: steps alternate
    sequence.beginStage("obstacles");
    obstacles_->recordFlags(sequence, params_, flagsDispatch_, s);
    sequence.endStage();
    if (obstacleCount > 0) {
      sequence.beginStage("forces");
      lbm_->recordForces(sequence, params_, obstacles_->flags(), s, stepParity, forces_, sweptCover_);
      sequence.endStage();
    }
    sequence.beginStage("lbm");
    lbm_->recordStep(sequence, params_, obstacles_->flags(), smoke_->smoke(), s, stepParity, sweptCover_);
    sequence.endStage();
    smoke_->recordSources(sequence, params_, obstacles_->flags(), s, inletCover_);
    smoke_->recordTransport(sequence, obstacles_->flags(), lbm_->macro());
  }
  sequence.beginStage("watchdog");
  speedStats_->record(sequence, lbm_->macro(), uint32_t(lbm_->cells()));
  densityStats_->record(sequence, smoke_->smoke(), uint32_t(smoke_->cells()));
  sequence.endStage();
  sequence.addReadback(speedStats_->resultBuffer());
  sequence.addReadback(densityStats_->resultBuffer());
  if (obstacleCount > 0) sequence.addReadback(forces_);
  sequence.finish();
  return sequence;
}

void Simulation::fillStepParameters(uint32_t steps) {
  auto* params = static_cast<StepParams*>(params_.mapped());
  auto* dispatch = static_cast<std::byte*>(flagsDispatch_.mapped());
  for (uint32_t s = 0; s < steps; ++s) {
    std::memset(&params[s], 0, sizeof(StepParams));
    obstacles_->fill(params[s], step_ + s);
    const VkDispatchIndirectCommand groups =
        flagsSchedule_.needsPass(params[s]) ? obstacles_->flagsGroups() : VkDispatchIndirectCommand{0, 0, 0};
    std::memcpy(dispatch + s * ObstacleSet::kFlagsDispatchStride, &groups, sizeof(groups));
  }
}

void Simulation::summarize(uint64_t firstStep, uint32_t steps, const std::vector<gpu::StageTime>& times,
                           const glm::vec4* forces, size_t obstacleCount, const gpu::Stats& speed,
                           const gpu::Stats& density) {
  AdvanceReport report;
  report.firstStep = firstStep;
  SmokePassTimes& smoke = report.times.smokePasses;
  for (const gpu::StageTime& t : times) {
    double* total = t.name == "obstacles"                      ? &report.times.obstacles
                    : t.name == "forces"                       ? &report.times.forces
                    : t.name == "lbm"                          ? &report.times.lbm
                    : t.name == SmokeTransport::kSourcesStage  ? &smoke.sources
                    : t.name == SmokeTransport::kActivityStage ? &smoke.activity
                    : t.name == SmokeTransport::kFluxesStage   ? &smoke.fluxes
                    : t.name == SmokeTransport::kLimiterStage  ? &smoke.limiter
                    : t.name == SmokeTransport::kUpdateStage   ? &smoke.update
                                                               : &report.times.watchdog;
    *total += t.milliseconds;
  }
  report.times.smoke = smoke.sources + smoke.activity + smoke.fluxes + smoke.limiter + smoke.update;
  if (forces)
    for (uint32_t s = 0; s < steps; ++s) {
      report.forces.emplace_back();
      for (size_t o = 0; o < obstacleCount; ++o)
        report.forces.back().push_back(glm::vec3(forces[s * kMaxObstacles + o]));
    }
  const float smokeCell = units_.cellSize / float(scene_.grid.smokeUpres);
  report.smokeMass = double(density.sum) * smokeCell * smokeCell * smokeCell;
  report.minDensity = density.minimum;
  report.maxDensity = density.maximum;
  report.maxLatticeSpeed = speed.maxAbs;
  report.maxSpeed = speed.maxAbs / units_.velocityScale;
  report_ = std::move(report);

  const WatchdogReport watchdog = checkWatchdog(speed, density, firstStep + steps, scene_.grid.size,
                                                smoke_->size(), scene_.grid.origin, units_.cellSize);
  if (watchdog.tripped) throw WatchdogError(watchdog.message);
}

void Simulation::record(VkCommandBuffer commands, uint64_t frame) {
  record(commands, frame, uint32_t(units_.stepsPerFrame));
}

void Simulation::record(VkCommandBuffer commands, uint64_t frame, uint32_t steps) {
  if (steps == 0 || steps > capacity_)
    throw std::invalid_argument("Simulation::record: " + std::to_string(steps) + " steps; 1 to " +
                                std::to_string(capacity_) + " a frame");
  checkRecordedFrame(frame);
  fillStepParameters(steps);
  gpu::Sequence& sequence = sequenceFor(steps, int(step_ % 2));
  if (std::optional<ObstacleSet::Voxelization> meshes = obstacles_->takeVoxelization()) {
    meshes->sequence->record(commands, frame);
    retired_.emplace_back(frame, std::move(meshes->sequence));
    for (gpu::Buffer& b : meshes->inputs) retiredBuffers_.emplace_back(frame, std::move(b));
  }
  sequence.record(commands, frame);
  recorded_.push_back({frame, step_, steps, &sequence, obstacles_->obstacleCount()});
  lastRecordedFrame_ = frame;
  step_ += steps;
}

void Simulation::checkRecordedFrame(uint64_t frame) {
  const uint64_t inFlight = context_->framesInFlight();
  while (!recorded_.empty() && recorded_.front().frame + inFlight <= frame) {
    const RecordedFrame done = recorded_.front();
    recorded_.erase(recorded_.begin());
    auto stats = [&](const gpu::ReduceStats& reduce) {
      gpu::Stats value;
      std::memcpy(&value, done.sequence->readback(reduce.resultBuffer(), done.frame).data(), sizeof(value));
      return value;
    };
    const glm::vec4* forces =
        done.obstacles > 0
            ? reinterpret_cast<const glm::vec4*>(done.sequence->readback(forces_, done.frame).data())
            : nullptr;
    summarize(done.firstStep, done.steps, done.sequence->timesOfFrame(done.frame), forces, done.obstacles,
              stats(*speedStats_), stats(*densityStats_));
    ++framesReported_;
  }
  // Replaced sequences that no frame in flight runs and no unread frame holds.
  std::erase_if(retired_, [&](const auto& r) { return r.first + inFlight < frame; });
  std::erase_if(retiredBuffers_, [&](const auto& r) { return r.first + inFlight < frame; });
}

void Simulation::advance(uint32_t steps) {
  // Every earlier submission has completed (advance waits for its own) unless an engine's recorded frames
  // hold them still.
  if (recorded_.empty()) {
    retired_.clear();
    retiredBuffers_.clear();
  }
  if (std::optional<ObstacleSet::Voxelization> meshes = obstacles_->takeVoxelization())
    meshes->sequence->submit();
  while (steps > 0) {
    const uint32_t n = std::min(steps, capacity_);
    fillStepParameters(n);
    gpu::Sequence& sequence = sequenceFor(n, int(step_ % 2));
    sequence.submit();
    const uint64_t firstStep = step_;
    step_ += n;
    std::vector<glm::vec4> forces;
    if (obstacles_->obstacleCount() > 0) forces = forces_.download<glm::vec4>();
    summarize(firstStep, n, sequence.stageTimes(), forces.empty() ? nullptr : forces.data(),
              obstacles_->obstacleCount(), speedStats_->result(), densityStats_->result());
    steps -= n;
  }
}

std::pair<io::DenseGrid, io::DenseGrid> Simulation::smokeGrids() const {
  const std::vector<glm::vec2> values = smoke_->download();
  io::DenseGrid density, temperature;
  for (io::DenseGrid* g : {&density, &temperature}) {
    g->size = smoke_->size();
    g->origin = scene_.grid.origin;
    g->dx = glm::vec3(units_.cellSize / float(scene_.grid.smokeUpres));
    g->values.resize(values.size());
  }
  for (size_t i = 0; i < values.size(); ++i) {
    density.values[i] = values[i].x;
    temperature.values[i] = values[i].y;
  }
  return {std::move(density), std::move(temperature)};
}

}  // namespace sixway::sim
