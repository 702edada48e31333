#pragma once
// A scene's fluid and smoke (docs/scene-format.md): the lattice Boltzmann flow around the scene's obstacles,
// the smoke it carries, and the volume the renderer draws, all on the GPU.
#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sixway/stage_time.h"

namespace sixway {

namespace runtime {
struct Access;
}  // namespace runtime

class Device;

// The smoke on the device, for engines that march or shade it themselves: density and temperature as one
// float per cell (x fastest, then y, then z; density per unit of the scene's smoke.extinction), on a lattice
// of cubic cells whose cell (0, 0, 0) has its corner at `origin` (scene space: placement() puts it in the
// world). The buffers stay the same for the simulation's life; a recorded frame writes them (storage-buffer
// writes, followed by a full barrier).
struct SmokeVolume {
  VkBuffer density = VK_NULL_HANDLE;
  VkBuffer temperature = VK_NULL_HANDLE;
  glm::ivec3 cells{0};
  glm::vec3 origin{0.0f};
  float cellSize = 0.0f;  // metres
};

// An engine's source of smoke (docs/embedding.md, "Emitters"): the lattice cells whose centres lie within
// `radius` of `position` gain density and temperature at these rates while `on`, and their flow is set to
// `velocity` (a jet) unless it is zero (then the fluid there moves freely: buoyancy lifts the smoke).
struct Emitter {
  glm::vec3 position{0.0f};      // world, m
  float radius = 0.1f;           // m
  glm::vec3 velocity{0.0f};      // world, m/s; at most maxEmitterSpeed()
  float densityRate = 1.0f;      // density per second, in the units of SmokeVolume
  float temperatureRate = 0.0f;  // per second (drives the scene's fluid.buoyancy.temperature)
  bool on = true;
};

// An engine's obstacle (docs/embedding.md, "Obstacles"): a sphere, a box along the smoke's axes (those of
// the placement), a capsule or a closed triangle mesh (a collision mesh), centred on `position`. The flow
// bounces off it, the smoke stays out of it and, with `shadows`, it shadows the smoke.
struct Obstacle {
  enum class Shape { Sphere, Box, Capsule, Mesh };
  Shape shape = Shape::Sphere;
  glm::vec3 position{0.0f};          // world, m: the centre (a mesh: its origin)
  float radius = 0.1f;               // sphere, capsule: m
  glm::vec3 size{0.2f};              // box: full edge lengths, m
  float height = 0.5f;               // capsule: end to end, caps included, at least 2 · radius (m)
  glm::vec3 axis{0.0f, 1.0f, 0.0f};  // capsule: world direction (any length but 0)
  // mesh: triangles as three indices each into `vertices` (its own space, counter-clockwise seen from
  // outside), turned by `rotation` (world) and scaled by `scale` about its origin; read during the call.
  std::span<const glm::vec3> vertices;
  std::span<const uint32_t> indices;
  glm::mat3 rotation{1.0f};
  float scale = 1.0f;
  bool shadows = true;
};

// A smoke domain made without a scene file (docs/embedding.md, "Without a scene file"): the lattice and the
// smoke's look; everything else as a scene file leaves it by default (docs/scene-format.md): no inlets, no
// obstacles and no lights (the engine's emitters, obstacles and lights), its camera looking at the domain.
struct SmokeDomain {
  glm::ivec3 cells{32, 48, 32};            // lattice cells along x, y (up), z (grid.size)
  float cellSize = 0.04f;                  // m (grid.cell_size)
  glm::vec3 origin{-0.64f, 0.0f, -0.64f};  // the lattice's corner in the scene (the placement's space), m
  float frameSeconds = 1.0f / 30.0f;       // simulated by record(commands, frame) (time.frame_dt)
  float viscosity = 1.5e-5f;               // m²/s (fluid.viscosity)
  float buoyancy = 2.0f;                   // lift per unit temperature (fluid.buoyancy.temperature)
  float extinction = 20.0f;                // 1/m per unit density (smoke.extinction)
  float albedo = 0.9f;                     // smoke.albedo
  float phaseG = 0.2f;                     // smoke.phase_g
  float dissipation = 0.0f;                // 1/s (smoke.dissipation)
  int lightmapSize = 64;  // texels square, 16 to 4096, a multiple of 16 (render.lightmap_size)
};

// A scene file's text held by the engine (docs/scene-format.md): no file is read but the meshes it names,
// relative to `directory`. `name` stands for the file in errors.
struct SceneText {
  std::string_view json;
  std::filesystem::path directory = ".";
  std::string name = "scene in memory";
};

class SmokeSimulation {
 public:
  // Loads the scene file; throws Error naming it (missing, malformed, beyond the device's limits).
  SmokeSimulation(Device& device, const std::filesystem::path& scene);
  // The same from the scene's text (read during construction).
  SmokeSimulation(Device& device, const SceneText& scene);
  // A domain without a scene file; an Error names the scene-file key of a value out of range.
  SmokeSimulation(Device& device, const SmokeDomain& domain);
  ~SmokeSimulation();
  SmokeSimulation(const SmokeSimulation&) = delete;
  SmokeSimulation& operator=(const SmokeSimulation&) = delete;

  // One frame of simulation (time.frame_dt) on sixway's own device; waits for it. Throws Error when the
  // watchdog finds the flow diverging (naming the scene and what to change).
  void advance();
  // Records one frame of simulation into `commands` — the engine's primary command buffer, recording,
  // outside a render pass — as frame number `frame` (increasing). Nothing waits; the watchdog checks the
  // frame recorded framesInFlight frames earlier, so its Error arrives that much later.
  void record(VkCommandBuffer commands, uint64_t frame);
  // The same for `seconds` of the engine's frame time (docs/embedding.md, "Frame time"): whole lattice steps
  // of stepSeconds() each, the remainder carried to the next call, at most maxStepsPerRecord() (the time
  // beyond them dropped: the smoke slows down rather than the frame). The smoke moves at the same speed at
  // any frame rate. Returns the steps recorded; 0: nothing is recorded and the volume stays as it was.
  // std::invalid_argument for negative or non-finite seconds.
  uint32_t record(VkCommandBuffer commands, uint64_t frame, double seconds);
  // One lattice step's simulated time: the scene's time.frame_dt over its steps per frame.
  double stepSeconds() const;
  // Default: twice the scene's steps per frame (real time down to half the scene's frame rate). 1 to
  // stepCapacity(); std::invalid_argument outside.
  void setMaxStepsPerRecord(uint32_t steps);
  uint32_t maxStepsPerRecord() const;
  uint32_t stepCapacity() const;

  // Back to the scene's first frame: the fluid at rest, no smoke, obstacles on the scene's motions. The
  // volume's buffers change (a renderer follows). With an engine's device, the GPU must have finished the
  // frames recorded so far (e.g. after vkDeviceWaitIdle).
  void restart();

  SmokeVolume volume() const;
  // Frames of time.frame_dt simulated (after record with seconds: the whole frames in the simulated time).
  int framesSimulated() const;
  double seconds() const;  // simulated time
  // GPU time of the simulation's steps in the last advance() ("sim/obstacles", "sim/lbm", "sim/smoke",
  // "sim/forces+watchdog"), or with an engine of the latest recorded frame whose times are in (framesInFlight
  // frames late); empty before.
  std::vector<StageTime> stageTimes() const;

  // Where the scene stands in the engine's world (docs/embedding.md, "Placement"): world = placement ·
  // scene, a rotation about the vertical axis (y stays up: the smoke rises along it) and a translation.
  // Renderers of this simulation take the engine's camera and lights in the world and give the lightmaps'
  // corners there; the obstacle calls below are in the world too. Default: the identity.
  // std::invalid_argument for anything else (a tilt, a scale, a projection, not finite).
  void setPlacement(const glm::mat4& worldFromScene);
  glm::mat4 placement() const;

  size_t obstacleCount() const;
  glm::vec3 obstaclePosition(size_t obstacle) const;  // world (m), now
  // Drags an obstacle toward `target` (world, m) in a straight line at a speed the lattice can follow
  // (at most maxObstacleSpeed()), arriving one scene frame from now or later; then it rests there.
  void steerObstacle(size_t obstacle, glm::vec3 target);
  // The same arriving `seconds` of simulated time from now (an engine's object: its position at the end of
  // the frame time passed to the next record), or later where that is faster than maxObstacleSpeed(): the
  // obstacle then lags behind and catches up. Moves within the cells covered so far record nothing again.
  // std::invalid_argument for an obstacle that does not exist, a target or time that is not finite, a
  // negative time.
  void steerObstacle(size_t obstacle, glm::vec3 target, double seconds);
  float maxObstacleSpeed()
      const;  // m/s: half fluid.max_lattice_velocity (the wall's speed adds to the flow's)
  // From the next recorded step on, these obstacles are the smoke's in place of the scene's (an empty list:
  // none). Call it each frame with the positions at the end of the frame time passed to the next record:
  // obstacle i with the same shape as in the last call moves there as steerObstacle(i, position, seconds)
  // does (given where it was given last, it goes on as it was: resting obstacles cost the lattice nothing);
  // any other (a new index, another shape, size, rotation or mesh, or a new placement) appears there at rest.
  // A call that changes shapes makes renderers build their obstacle meshes at their next frame; a new mesh is
  // copied and prepared during the call and voxelized by GPU work in the next record (host work, no
  // submission); moves within the cells covered so far record nothing again. restart() returns to the scene's
  // obstacles.
  // std::invalid_argument for more than maxObstacles(), a value that is not finite, a size or radius <= 0,
  // a capsule shorter than its diameter or without an axis, a mesh without triangles, with an index out of
  // range or a rotation that is not one, a negative time; an Error for a mesh too fine for the lattice.
  void setObstacles(const std::vector<Obstacle>& obstacles, double seconds);
  size_t maxObstacles() const;
  // Scales the scene's inlets' velocity, in [0, maxInletStrength()]; std::invalid_argument outside.
  void setInletStrength(float strength);
  float inletStrength() const;
  float maxInletStrength() const;
  // From the next recorded step on, these emitters are the smoke's sources in place of the scene's inlets
  // (an empty list: none). Call it each frame to move them, switch them or change their rates; moves within
  // the cells covered so far record nothing again. std::invalid_argument for more than maxEmitters(), a
  // speed beyond maxEmitterSpeed(), a position that is not finite, a negative or non-finite radius or rate.
  void setEmitters(const std::vector<Emitter>& emitters);
  size_t maxEmitters() const;
  float maxEmitterSpeed() const;  // m/s: fluid.max_lattice_velocity in the scene's lattice units

 private:
  friend runtime::Access;  // sixway's own tools (src/runtime/internal.h, not installed)
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sixway
