#version 460
// Sets every cell's populations to the equilibrium of the velocity and density in `macro`, kept as a step of
// parity PARITY finds them (lbm_in_place.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "sim_spec.glsl"

layout(local_size_x = 64) in;
layout(constant_id = SIM_SPEC_NX) const int NX = 1;
layout(constant_id = SIM_SPEC_NY) const int NY = 1;
layout(constant_id = SIM_SPEC_NZ) const int NZ = 1;
layout(constant_id = SIM_SPEC_FACE_XM) const uint FACE_XM = 0u;  // boundary type per face (sim_grid.glsl)
layout(constant_id = SIM_SPEC_FACE_XP) const uint FACE_XP = 0u;
layout(constant_id = SIM_SPEC_FACE_YM) const uint FACE_YM = 0u;
layout(constant_id = SIM_SPEC_FACE_YP) const uint FACE_YP = 0u;
layout(constant_id = SIM_SPEC_FACE_ZM) const uint FACE_ZM = 0u;
layout(constant_id = SIM_SPEC_FACE_ZP) const uint FACE_ZP = 0u;
layout(constant_id = SIM_SPEC_PARITY) const uint PARITY = 0u;

const ivec3 SIZE = ivec3(NX, NY, NZ);
const uint CELLS = uint(NX * NY * NZ);

#include "linear_index.glsl"
#include "lbm_d3q19.glsl"
#include "lbm_lattice.glsl"
#include "sim_grid.glsl"

layout(std430, binding = 0) readonly buffer Macro_ { vec4 macro[]; };
layout(std430, binding = 1) buffer A0 { LbmPopulation a0[]; };
layout(std430, binding = 2) buffer A1 { LbmPopulation a1[]; };
layout(std430, binding = 3) buffer A2 { LbmPopulation a2[]; };
layout(std430, binding = 4) buffer A3 { LbmPopulation a3[]; };

#include "lbm_in_place.glsl"

void main() {
  uint cell = linearInvocationIndex();
  if (cell >= CELLS) return;
  ivec3 p = cellOf(cell, SIZE);
  vec4 m = macro[cell];
  [[unroll]] for (int j = 0; j < Q; ++j) {
    Slot s = keptSlot(j, p, PARITY);
    SIXWAY_STORE(s.population, s.cell, equilibrium(j, m.w, m.xyz), a0, a1, a2, a3)
  }
}
