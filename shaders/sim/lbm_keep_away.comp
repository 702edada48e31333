#version 460
// Before an in-place step with interpolated bounce-back: each fluid cell of the obstacles' box next to the
// box of solid cells copies the 19 populations it sent in the step before, f*_i(x), as stored, into `away` (the lattice's
// layout over the box: slot i of box cell b is word (i % 5) · box cells + b of buffer i / 5). The rule for a
// wall farther than half a link (q > ½, sim_bounce_back.glsl) needs f*_i(x), the population x sent away from
// the wall, which the next cell, x + C[i], overwrites in place (lbm_in_place.glsl): lbm_step reads the copy.
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
layout(constant_id = SIM_SPEC_PARITY) const uint PARITY = 0u;  // the coming step's

const ivec3 SIZE = ivec3(NX, NY, NZ);

#include "linear_index.glsl"
#include "lbm_d3q19.glsl"
#include "lbm_lattice.glsl"
#include "sim_grid.glsl"

layout(std430, binding = 0) readonly buffer A0 { LbmPopulation a0[]; };
layout(std430, binding = 1) readonly buffer A1 { LbmPopulation a1[]; };
layout(std430, binding = 2) readonly buffer A2 { LbmPopulation a2[]; };
layout(std430, binding = 3) readonly buffer A3 { LbmPopulation a3[]; };
layout(std430, binding = 4) writeonly buffer W0 { LbmPopulation w0[]; };
layout(std430, binding = 5) writeonly buffer W1 { LbmPopulation w1[]; };
layout(std430, binding = 6) writeonly buffer W2 { LbmPopulation w2[]; };
layout(std430, binding = 7) writeonly buffer W3 { LbmPopulation w3[]; };
layout(std430, binding = 8) readonly buffer Params { StepParams params[]; };
layout(std430, binding = 9) readonly buffer Flags { uint flags[]; };
layout(push_constant) uniform Push {
  uint step;
  uint unused[3];
  ivec4 boxMin;   // xyz: the obstacles' swept box (ObstacleSet::sweptBox)
  ivec4 boxSize;  // xyz: its cells per axis
} push;

#include "lbm_in_place.glsl"

void main() {
  uint index = linearInvocationIndex();
  uint boxCells = uint(push.boxSize.x * push.boxSize.y * push.boxSize.z);
  if (index >= boxCells) return;
  ivec3 p = push.boxMin.xyz + cellOf(index, push.boxSize.xyz);
  // Only a fluid cell with a neighbour in the box of solid cells (sim_grid.glsl) can have a wall link.
  bool linked = false;
  [[unroll]] for (int i = 1; i < Q; ++i) linked = linked || nearSolid(params[push.step], wrapPeriodic(p - C[i]));
  if (!linked || isSolid(flags[cellIndex(p, SIZE)])) return;
  [[unroll]] for (int i = 0; i < Q; ++i) {
    Slot s = keptSlot(i, p, PARITY);
    uint word = uint(i % POPULATIONS_PER_BUFFER) * boxCells + index;
    // Copied as stored: no decoding, so the step reads exactly what the lattice held.
    SIXWAY_STORE_RAW(i, word, SIXWAY_RAW(s.population, populationWord(s.population, s.cell), a0, a1, a2, a3),
                     w0, w1, w2, w3)
  }
}
