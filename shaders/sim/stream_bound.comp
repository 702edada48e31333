#version 460
// The memory ceiling of a lattice update on this device (tests/sim/bench_stream_bound.cpp, not used by the
// simulation): lbm_step.comp's traffic, 19 populations read and 19 written per cell in its storage layout, and
// nothing else (no collision, no flags, periodic wrap), from one lattice into another. With PULL the reads
// gather from the neighbours (as a step of parity 0 does, lbm_in_place.glsl); without, every population stays
// in its cell (as in a step of parity 1). Its bandwidth is the most a compute kernel with the LBM's access
// pattern gets from the device, next to a plain buffer copy.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "sim_spec.glsl"

layout(local_size_x = 64) in;
layout(constant_id = SIM_SPEC_NX) const int NX = 1;
layout(constant_id = SIM_SPEC_NY) const int NY = 1;
layout(constant_id = SIM_SPEC_NZ) const int NZ = 1;
layout(constant_id = SIM_SPEC_PULL) const bool PULL = true;

const uint CELLS = uint(NX * NY * NZ);
const uint STORED_CELLS = CELLS;  // two lattices without ghost cells (lbm_lattice.glsl)
const ivec3 SIZE = ivec3(NX, NY, NZ);

#include "linear_index.glsl"
#include "lbm_d3q19.glsl"
#include "lbm_lattice.glsl"
#include "sim_grid.glsl"

layout(std430, binding = 0) readonly buffer F0 { LbmPopulation f0[]; };
layout(std430, binding = 1) readonly buffer F1 { LbmPopulation f1[]; };
layout(std430, binding = 2) readonly buffer F2 { LbmPopulation f2[]; };
layout(std430, binding = 3) readonly buffer F3 { LbmPopulation f3[]; };
layout(std430, binding = 4) writeonly buffer G0 { LbmPopulation g0[]; };
layout(std430, binding = 5) writeonly buffer G1 { LbmPopulation g1[]; };
layout(std430, binding = 6) writeonly buffer G2 { LbmPopulation g2[]; };
layout(std430, binding = 7) writeonly buffer G3 { LbmPopulation g3[]; };

void main() {
  uint cell = linearInvocationIndex();
  if (cell >= CELLS) return;
  ivec3 p = cellOf(cell, SIZE);
  [[unroll]] for (int i = 0; i < Q; ++i) {
    uint source = PULL ? cellIndex((p - C[i] + SIZE) % SIZE, SIZE) : cell;
    SIXWAY_STORE(i, cell, SIXWAY_LOAD(i, source, f0, f1, f2, f3), g0, g1, g2, g3)
  }
}
