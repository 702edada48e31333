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
layout(std430, binding = 1) writeonly buffer G0 { float g0[]; };
layout(std430, binding = 2) writeonly buffer G1 { float g1[]; };
layout(std430, binding = 3) writeonly buffer G2 { float g2[]; };
layout(std430, binding = 4) writeonly buffer G3 { float g3[]; };

void main() {
  uint cell = linearInvocationIndex();
  if (cell >= CELLS) return;
  vec4 m = macro[cell];
  [[unroll]] for (int i = 0; i < Q; ++i) {
    float value = equilibrium(i, m.w, m.xyz);
    uint word = populationWord(i, cell);
    if (i < 5) g0[word] = value;
    else if (i < 10) g1[word] = value;
    else if (i < 15) g2[word] = value;
    else g3[word] = value;
  }
}
