#pragma once
// The smoke simulation of one scene: obstacles and inlets → lattice Boltzmann flow → smoke
// sources and transport, all on the GPU. Each submission of n steps is recorded once into a
// gpu::Sequence and replayed; between submissions only StepParams (obstacle positions, inlet
// switches) are written by the host, and a few bytes (watchdog, forces) are read back.
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/reduce_stats.h"
#include "gpu/sequence.h"
#include "io/dense_grid.h"
#include "scene/scene.h"
#include "sim/flags_schedule.h"
#include "sim/lattice_units.h"
#include "sim/lbm_solver.h"
#include "sim/obstacle_set.h"
#include "sim/smoke_transport.h"

namespace sixway::sim {

// The smoke step's passes, timed one by one (SmokeTransport): sources, then per substep the FCT fluxes,
// limiter and update. `smoke` is their sum.
struct SmokePassTimes {
  double sources = 0, activity = 0, fluxes = 0, limiter = 0, update = 0;  // ms, GPU timestamps
};

struct StepTimes {
  double obstacles = 0, forces = 0, lbm = 0, smoke = 0, watchdog = 0;  // ms, GPU timestamps
  SmokePassTimes smokePasses;
  double total() const { return obstacles + forces + lbm + smoke + watchdog; }
};

struct AdvanceReport {
  uint64_t firstStep = 0;                      // the step number of the first of these steps
  std::vector<std::vector<glm::vec3>> forces;  // [step][obstacle], lattice units (ρ₀ = 1, per step²)
  double smokeMass = 0;                        // Σ density · smoke-cell volume (density · m³)
  float minDensity = 0, maxDensity = 0;
  float maxSpeed = 0;         // m/s
  float maxLatticeSpeed = 0;  // cells/step
  StepTimes times;            // for all the steps of this submission
};

class Simulation {
 public:
  Simulation(const gpu::Context& context, const gpu::PipelineCache& cache, const scene::Scene& scene);
  ~Simulation();

  // Runs `steps` lattice steps (in submissions of at most stepsPerFrame). Throws WatchdogError.
  void advance(uint32_t steps);
  // Records one frame's steps (scene::lbmStepsPerFrame) into `commands`, a caller's command buffer, as frame
  // `frame` (gpu::Sequence::record): nothing waits. The measurements of the frame recorded
  // Context::framesInFlight() frames earlier, complete by then, become report(), and the watchdog checks
  // them: a WatchdogError arrives that many frames late.
  void record(VkCommandBuffer commands, uint64_t frame);
  // The same with `steps` lattice steps, 1..stepCapacity() (std::invalid_argument outside).
  void record(VkCommandBuffer commands, uint64_t frame, uint32_t steps);
  // The most steps one submission or recorded frame holds.
  uint32_t stepCapacity() const { return capacity_; }
  // Sets the velocity (m/s) and density (ρ/ρ₀) of every lattice cell, x fastest, and the
  // populations to their equilibrium; for analytic initial conditions.
  void setFlow(const std::vector<glm::vec3>& velocity, const std::vector<float>& density);

  // Drags obstacle `obstacle` toward `target` (world, m) from where it is now: a straight line arriving
  // `seconds` from now (default: one frame), or later where that is faster than half the lattice's speed
  // limit (fluid.max_lattice_velocity; the moving wall adds its speed to the flow's); then it stays there.
  // Bounce-back follows the motion's velocity. std::invalid_argument for a negative or non-finite time or a
  // target that is not finite.
  void steerObstacle(size_t obstacle, glm::vec3 target, std::optional<double> seconds = std::nullopt);
  // The fastest an obstacle moves (m/s): half the lattice's speed limit.
  double obstacleSpeedLimit() const;
  // Replaces every obstacle (the scene's, or an earlier set) from the next step on: any shapes in scene
  // coordinates, each at rest where its shape says or on its motion (an engine's obstacles, which it then
  // steers); meshes are voxelized by GPU work that the next record or advance runs first. scene().obstacles
  // follows and obstacleSetsMade() counts up. std::invalid_argument for more than kMaxObstacles;
  // io::InputError for a mesh too fine for the lattice (nothing changed then).
  void setObstacles(std::vector<scene::Obstacle> obstacles);
  // How many times setObstacles has replaced the obstacles: what was made for the earlier ones (a renderer's
  // meshes) is out of date.
  uint64_t obstacleSetsMade() const { return obstacleSetsMade_; }
  // Replaces the inlets by these emitters from the next step on (ObstacleSet::setEmitters).
  // std::invalid_argument for more than kMaxInlets, a speed beyond fluid.max_lattice_velocity, a position
  // that is not finite, a negative or non-finite radius or rate.
  void setEmitters(std::span<const Emitter> emitters);
  // The fastest an emitter may push the flow (m/s): fluid.max_lattice_velocity.
  double emitterSpeedLimit() const;
  // How many step sequences were recorded: a steered obstacle or a moved emitter that leaves the cells the
  // recorded ones cover records them again (and grows what they cover).
  uint64_t sequencesRecorded() const { return sequencesRecorded_; }
  // The obstacle's motion as the simulation uses it (the scene's, or the steered one).
  const std::optional<scene::Motion>& obstacleMotion(size_t obstacle) const {
    return obstacles_->motion(obstacle);
  }
  // Scales the inlets' velocity, in [0, maxInletStrength()]; throws std::invalid_argument outside.
  void setInletStrength(float strength);
  // The largest inlet strength whose fastest inlet stays within fluid.max_lattice_velocity (at least 1, at
  // most 2; 1 without inlets).
  float maxInletStrength() const;
  float inletStrength() const { return inletStrength_; }

  // The last submission's measurements (forces of every step in it).
  const AdvanceReport& report() const { return report_; }
  // How many recorded frames' measurements have become report() (record's readbacks).
  uint64_t framesReported() const { return framesReported_; }
  uint64_t step() const { return step_; }
  // Steps whose cell flags were computed (the others kept the last: FlagsSchedule).
  uint64_t flagPasses() const { return flagsSchedule_.passes(); }
  double seconds() const { return double(step_) * units_.stepSeconds; }
  const LatticeUnits& units() const { return units_; }
  const scene::Scene& scene() const { return scene_; }

  const LbmSolver& lbm() const { return *lbm_; }
  SmokeTransport& smoke() { return *smoke_; }
  const ObstacleSet& obstacles() const { return *obstacles_; }
  // Density and temperature on the smoke grid, for VDB output (reads back the smoke grid).
  std::pair<io::DenseGrid, io::DenseGrid> smokeGrids() const;

 private:
  gpu::Sequence& sequenceFor(uint32_t steps, int parity);
  void fillStepParameters(uint32_t steps);
  // report_ from the measurements of `steps` steps from `firstStep`; throws WatchdogError when they trip it.
  void summarize(uint64_t firstStep, uint32_t steps, const std::vector<gpu::StageTime>& times,
                 const glm::vec4* forces, size_t obstacleCount, const gpu::Stats& speed,
                 const gpu::Stats& density);
  void checkRecordedFrame(uint64_t frame);
  // Grows the boxes the sequences are recorded for until they hold the obstacles' swept box and the inlets'
  // box; sequences recorded for smaller ones are retired.
  void coverBoxes();
  // Moves every recorded sequence to retired_ (frames in flight may run them): the next steps record anew.
  void retireSequences();

  const gpu::Context* context_;
  scene::Scene scene_;
  LatticeUnits units_;
  std::unique_ptr<ObstacleSet> obstacles_;
  std::unique_ptr<LbmSolver> lbm_;
  std::unique_ptr<SmokeTransport> smoke_;
  std::unique_ptr<gpu::ReduceStats> speedStats_, densityStats_;
  uint32_t capacity_;  // steps per submission
  gpu::Buffer params_, forces_;
  gpu::Buffer flagsDispatch_;  // per step slot: the flags pass's workgroups (ObstacleSet::recordFlags)
  FlagsSchedule flagsSchedule_;
  // By steps and parity; with and without obstacles (their forces stage and readback).
  std::map<std::tuple<uint32_t, int, bool>, std::unique_ptr<gpu::Sequence>> sequences_;
  // record(): what each recent frame ran (its results come back framesInFlight frames later), and the
  // sequences a steered obstacle replaced, kept until no frame in flight can use them.
  struct RecordedFrame {
    uint64_t frame, firstStep;
    uint32_t steps;
    gpu::Sequence* sequence;
    size_t obstacles;  // as the frame was recorded: its sequence reads back forces when there are any
  };
  std::vector<RecordedFrame> recorded_;
  std::vector<std::pair<uint64_t, std::unique_ptr<gpu::Sequence>>> retired_;
  std::vector<std::pair<uint64_t, gpu::Buffer>> retiredBuffers_;  // a replaced occupancy, meshes' inputs
  using Box = std::pair<glm::ivec3, glm::ivec3>;                  // lattice cells [min, max)
  Box sweptCover_, inletCover_;                                   // what the recorded sequences visit
  uint64_t sequencesRecorded_ = 0;
  uint64_t obstacleSetsMade_ = 0;
  uint64_t lastRecordedFrame_ = 0;
  uint64_t framesReported_ = 0;
  uint64_t step_ = 0;
  float inletStrength_ = 1.0f;
  AdvanceReport report_;
};

}  // namespace sixway::sim
