#pragma once
// Host mirrors of the std430 structs in shaders/common/sim_grid.glsl. Positions are in lattice
// coordinates (cell centres at integer + 0.5), velocities in cells per lattice step.
#include <glm/glm.hpp>

#include <cstdint>

namespace sixway::sim {

inline constexpr uint32_t kMaxObstacles = 16;
inline constexpr uint32_t kMaxInlets = 8;

enum class ShapeCode : uint32_t { Sphere = 0, Cylinder = 1, Box = 2, Mesh = 3, Capsule = 4 };

struct GpuObstacle {
  glm::vec4 centre;  // w: ShapeCode
  glm::vec4 velocity;
  glm::vec4 axis;         // cylinder: unit axis, w: half height; capsule: w: half the segment's length
  glm::vec4 size;         // sphere/cylinder: x radius; box: half sizes
  glm::vec4 rotation[3];  // mesh: rows of lattice→object (rotationᵀ · cell size / scale)
  glm::vec4 meshOrigin;   // mesh: object-space grid corner; w: voxel size (object units)
  glm::ivec4 meshGrid;    // mesh: voxels; w: first word in the occupancy buffer
};

enum class InletShape : uint32_t { Disk = 0, Box = 1, Ball = 2 };
// GpuInlet::smoke.w bits (INLET_ADDS, INLET_SETS_FLOW): the cells gain smoke.xy each step rather than hold
// it; the flow there is set to the inlet's velocity.
inline constexpr uint32_t kInletAdds = 1, kInletSetsFlow = 2;

struct GpuInlet {
  glm::vec4 centre;    // disk, ball: centre; box: min corner; w: InletShape
  glm::vec4 normal;    // disk: normal, w radius; ball: w radius; box: max corner
  glm::vec4 velocity;  // w: noise amplitude
  glm::vec4 smoke;     // density, temperature, active (0/1), kInlet* bits
};

struct StepParams {
  GpuObstacle obstacles[kMaxObstacles];
  GpuInlet inlets[kMaxInlets];
  glm::uvec4 counts;    // obstacles, inlets, step number
  glm::ivec4 solidMin;  // box of the cells solid this step or the last, grown by a cell (max exclusive)
  glm::ivec4 solidMax;
};

static_assert(sizeof(GpuObstacle) == 144 && sizeof(GpuInlet) == 64);
static_assert(sizeof(StepParams) == 144 * kMaxObstacles + 64 * kMaxInlets + 48);

}  // namespace sixway::sim
