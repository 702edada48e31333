#pragma once
// The scene's obstacles and inlets in lattice coordinates, at any step: keyframed motion is
// evaluated on the host and handed to the shaders in StepParams. Meshes are voxelized once on
// the GPU into an occupancy grid in their own object space, so they can move rigidly too.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "scene/scene.h"
#include "sim/lattice_units.h"
#include "sim/sim_params.h"

namespace sixway::sim {

// A source of smoke set from outside the scene file (an engine's, each frame): a ball of lattice cells (their
// centres within `radius` of `centre`) that gains density and temperature at these rates while `on`, and
// whose flow is set to `velocity` unless that is zero (then the fluid there moves freely).
struct Emitter {
  glm::vec3 centre{0.0f};                            // scene space, m
  float radius = 0.0f;                               // m
  glm::vec3 velocity{0.0f};                          // m/s
  float densityRate = 0.0f, temperatureRate = 0.0f;  // per second
  bool on = true;
};

class ObstacleSet {
 public:
  ObstacleSet(const gpu::Context& context, const gpu::PipelineCache& cache, const scene::Scene& scene,
              const LatticeUnits& units);

  // Obstacles and inlets as they are at lattice step `step` (time = step · stepSeconds).
  void fill(StepParams& params, uint64_t step) const;
  // The lattice cells [min, max) that any obstacle covers at any time of its motion, or neighbours, grown
  // like StepParams' solid box: outside it no bounce-back link exists, ever. Empty (min = max) without
  // obstacles.
  std::pair<glm::ivec3, glm::ivec3> sweptBox() const;
  // The lattice cells [min, max) that hold every inlet cell (insideInlet in sim_grid.glsl tests cell
  // centres), clamped to the lattice. Empty without inlets.
  std::pair<glm::ivec3, glm::ivec3> inletBox() const;
  // Replaces the motion of `obstacle` (none: at rest where its shape says), e.g. while a user drags it.
  // sweptBox() follows the new motion: sequences recorded with the old box must be recorded again.
  void setMotion(size_t obstacle, std::optional<scene::Motion> motion);
  const std::optional<scene::Motion>& motion(size_t obstacle) const { return obstacles_.at(obstacle).motion; }
  // Where the obstacle's centre (a mesh: its translation) is at `seconds`, in world coordinates (m).
  glm::vec3 positionAt(size_t obstacle, double seconds) const;
  // Replaces every obstacle from the next step on (at most kMaxObstacles, std::invalid_argument beyond).
  // sweptBox() follows: sequences recorded with the old box must be recorded again unless it holds the new.
  // With meshes in the new set: returns the occupancy buffer it replaced (sequences recorded with it must be
  // recorded again, and it kept while frames in flight may read it), and the new one is filled by the work
  // takeVoxelization() hands over. Nothing changes when a mesh needs too many voxels (io::InputError).
  std::optional<gpu::Buffer> setObstacles(std::span<const scene::Obstacle> obstacles);
  // The voxelization of the last set's meshes, once: recorded or submitted before the next step, and kept
  // (with the buffers it reads) while frames in flight may run it.
  struct Voxelization {
    std::vector<gpu::Buffer> inputs;
    std::unique_ptr<gpu::Sequence> sequence;
  };
  std::optional<Voxelization> takeVoxelization() { return std::exchange(pending_, std::nullopt); }
  // Scales the scene's inlets' velocity (not their smoke) from the next step on; 1 is the scene's.
  void setInletStrength(float strength) { inletStrength_ = strength; }
  // Replaces every inlet (the scene's or earlier emitters) from the next step on; at most kMaxInlets.
  // inletBox() follows: sequences recorded with the old box must be recorded again unless it holds the new.
  void setEmitters(std::span<const Emitter> emitters);
  // Marks each lattice cell with the obstacle and the inlet covering it at step params[slot], in as many
  // workgroups as dispatchArgs[slot] says (a VkDispatchIndirectCommand every kFlagsDispatchStride bytes):
  // flagsGroups(), or none where FlagsSchedule skips the step.
  void recordFlags(gpu::Sequence& sequence, const gpu::Buffer& params, const gpu::Buffer& dispatchArgs,
                   uint32_t slot) const;
  VkDispatchIndirectCommand flagsGroups() const { return flagsGroups_; }
  static constexpr uint64_t kFlagsDispatchStride = 16;

  // Per lattice cell: obstacle and inlet (shaders/common/sim_grid.glsl, FLAG_*).
  const gpu::Buffer& flags() const { return flags_; }
  const gpu::Buffer& occupancy() const { return occupancy_; }
  size_t obstacleCount() const { return obstacles_.size(); }

 private:
  struct Placed {
    GpuObstacle shape;  // at rest; centre replaced by the motion's position
    std::optional<scene::Motion> motion;
    glm::vec3 halfExtent;  // of an axis-aligned box around the centre that holds the shape, cells
  };
  struct TimedInlet {
    GpuInlet inlet;
    float start, stop;  // s
    bool scaled;        // by the inlet strength (the scene's inlets; an emitter's velocity is its own)
  };
  // A shape (not a mesh's voxels) in lattice coordinates.
  Placed placed(const scene::Obstacle& obstacle) const;
  // Plans the occupancy grids of the meshes among `obstacles` (obstacles_[i] is obstacles[i]) into a fresh
  // occupancy_ and records their voxelization (no sequence without meshes).
  Voxelization voxelize(std::span<const scene::Obstacle> obstacles);
  glm::vec3 centreAt(size_t obstacle, uint64_t step) const;  // lattice coordinates

  const gpu::Context* context_;
  const gpu::PipelineCache* cache_;
  LatticeUnits units_;
  glm::vec3 origin_;
  glm::ivec3 size_;
  uint64_t cells_;  // of the lattice
  gpu::Buffer flags_;
  std::unique_ptr<gpu::Pipeline> flagsPipeline_;
  VkDispatchIndirectCommand flagsGroups_;
  std::vector<Placed> obstacles_;
  std::vector<TimedInlet> inlets_;
  float inletStrength_ = 1.0f;
  gpu::Buffer occupancy_;
  std::unique_ptr<gpu::Pipeline> voxelizePipeline_;
  std::optional<Voxelization> pending_;
};

}  // namespace sixway::sim
