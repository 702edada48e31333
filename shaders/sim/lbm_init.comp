#version 460
// Sets every cell's populations to the equilibrium of the velocity and density in `macro`.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "sim_spec.glsl"

layout(local_size_x = 64) in;
layout(constant_id = SIM_SPEC_CELLS) const uint CELLS = 1u;

#include "linear_index.glsl"
#include "lbm_d3q19.glsl"
#include "lbm_lattice.glsl"

layout(std430, binding = 0) readonly buffer Macro_ { vec4 macro[]; };
layout(std430, binding = 1) writeonly buffer G0 { LbmPopulation g0[]; };
layout(std430, binding = 2) writeonly buffer G1 { LbmPopulation g1[]; };
layout(std430, binding = 3) writeonly buffer G2 { LbmPopulation g2[]; };
layout(std430, binding = 4) writeonly buffer G3 { LbmPopulation g3[]; };

void main() {
  uint cell = linearInvocationIndex();
  if (cell >= CELLS) return;
  vec4 m = macro[cell];
  [[unroll]] for (int i = 0; i < Q; ++i) SIXWAY_STORE(i, cell, equilibrium(i, m.w, m.xyz), g0, g1, g2, g3)
}
