#version 460
// The sparse transport's dissipation (sim_bricks.glsl), once per lattice step before smoke_sources.comp sets the
// inlets: the smoke of the bricks active in the last substep decays; every other cell holds none.
#extension GL_GOOGLE_include_directive : require
#include "sim_spec.glsl"

layout(local_size_x = 16, local_size_y = 2, local_size_z = 2) in;  // one brick
layout(constant_id = SIM_SPEC_NX) const int NX = 1;
layout(constant_id = SIM_SPEC_NY) const int NY = 1;
layout(constant_id = SIM_SPEC_NZ) const int NZ = 1;
layout(constant_id = SIM_SPEC_SMOKE_UPRES) const int SMOKE_UPRES = 1;
layout(constant_id = SIM_SPEC_DECAY) const float DECAY = 1.0;  // exp(−dissipation · dt) per lattice step
const bool SPARSE = true;                                       // sim_fct_cell.glsl: the active list

#include "sim_grid.glsl"
#include "sim_smoke.glsl"
#include "sim_bricks.glsl"

layout(std430, binding = 0) readonly buffer Header { uint header[]; };
layout(std430, binding = 1) readonly buffer ActiveList { uint activeList[]; };
layout(std430, binding = 2) buffer Smoke { vec2 smoke[]; };

#include "sim_fct_cell.glsl"

void main() {
  ivec3 s;
  if (!fctCell(s)) return;
  smoke[cellIndex(s, SMOKE)] *= DECAY;
}
