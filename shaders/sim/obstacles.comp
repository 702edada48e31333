#version 460
// Marks every lattice cell with the obstacle that covers it (first in the list wins) and the inlet
// that forces it, for the current step; remembers the obstacle that covered it in the previous step.
#extension GL_GOOGLE_include_directive : require
#include "sim_spec.glsl"

layout(local_size_x = 64) in;
layout(constant_id = SIM_SPEC_NX) const int NX = 1;
layout(constant_id = SIM_SPEC_NY) const int NY = 1;
layout(constant_id = SIM_SPEC_NZ) const int NZ = 1;

#include "linear_index.glsl"
#include "sim_grid.glsl"

layout(std430, binding = 0) readonly buffer Params { StepParams params[]; };
layout(std430, binding = 1) readonly buffer Occupancy { uint occupancy[]; };
layout(std430, binding = 2) buffer Flags { uint flags[]; };
layout(push_constant) uniform Push { uint step; } push;

// Inside where the parity along at least two axes says so (voxelize_mesh.comp).
bool meshOccupied(uint word) { return bitCount(occupancy[word] & 7u) >= 2; }
#include "sim_obstacles.glsl"

void main() {
  const ivec3 size = ivec3(NX, NY, NZ);
  uint index = linearInvocationIndex();
  if (index >= uint(NX * NY * NZ)) return;
  vec3 p = vec3(cellOf(index, size)) + 0.5;
  uint previous = flags[index];
  uint solid = 0u;
  uint obstacles = nearSolid(params[push.step], cellOf(index, size)) ? params[push.step].counts.x : 0u;
  for (uint o = 0u; o < obstacles && solid == 0u; ++o)
    if (insideObstacle(params[push.step].obstacles[o], p)) solid = o + 1u;
  uint inlet = 0u;
  for (uint i = 0u; i < params[push.step].counts.y && inlet == 0u && solid == 0u; ++i)
    if (params[push.step].inlets[i].smoke.z != 0.0 && insideInlet(params[push.step].inlets[i], p)) inlet = i + 1u;
  flags[index] = solid | (obstacleOf(previous) << FLAG_PREVIOUS_SHIFT) | (inlet << FLAG_INLET_SHIFT);
}
