#version 460
// Flux-corrected transport, pass 2 of 3: Zalesak's limiter ratios R+ and R− per cell, from the
// antidiffusive fluxes in and out and the bounds of the old and low-order values over the cell
// and its face neighbours, so that the corrected update creates no new extrema.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "sim_spec.glsl"

layout(local_size_x = 16, local_size_y = 2, local_size_z = 2) in;  // one brick (sim_bricks.glsl)
layout(constant_id = SIM_SPEC_NX) const int NX = 1;
layout(constant_id = SIM_SPEC_NY) const int NY = 1;
layout(constant_id = SIM_SPEC_NZ) const int NZ = 1;
layout(constant_id = SIM_SPEC_SMOKE_UPRES) const int SMOKE_UPRES = 1;
layout(constant_id = SIM_SPEC_SPARSE) const bool SPARSE = false;
layout(constant_id = SIM_SPEC_PERIODIC_X) const bool PERIODIC_X = false;
layout(constant_id = SIM_SPEC_PERIODIC_Y) const bool PERIODIC_Y = false;
layout(constant_id = SIM_SPEC_PERIODIC_Z) const bool PERIODIC_Z = false;

#include "sim_grid.glsl"
#include "sim_smoke.glsl"
#include "sim_bricks.glsl"
#include "sim_fct.glsl"
#include "sim_fct_fluxes.glsl"

layout(std430, binding = 0) readonly buffer Flags { uint flags[]; };
layout(std430, binding = 1) readonly buffer Smoke { vec2 smoke[]; };
layout(std430, binding = 2) readonly buffer LowOrder { vec2 lowOrder[]; };
layout(std430, binding = 3) readonly buffer AntidiffusiveX { vec2 antidiffusiveX[]; };
layout(std430, binding = 4) readonly buffer AntidiffusiveY { vec2 antidiffusiveY[]; };
layout(std430, binding = 5) readonly buffer AntidiffusiveZ { vec2 antidiffusiveZ[]; };
layout(std430, binding = 6) writeonly buffer Ratios { vec4 ratios[]; };  // R+ (xy), R− (zw)
layout(std430, binding = 7) readonly buffer Header { uint header[]; };         // sim_bricks.glsl
layout(std430, binding = 8) readonly buffer ActiveList { uint activeList[]; };

#include "sim_fct_cell.glsl"

void main() {
  ivec3 s;
  if (!fctCell(s)) return;
  uint index = cellIndex(s, SMOKE);
  vec2 qtd = lowOrder[index];
  vec2 highest = max(smoke[index], qtd), lowest = min(smoke[index], qtd);
  vec2 in_ = vec2(0.0), out_ = vec2(0.0);  // antidiffusive fluxes into and out of the cell
  [[unroll]] for (int a = 0; a < 3; ++a)
    [[unroll]] for (int side = 0; side < 2; ++side) {
      ivec3 n = s;
      n[a] += side == 0 ? -1 : 1;
      if (!wrapNeighbour(n, a)) continue;
      uint ni = cellIndex(n, SMOKE);
      if (!isSolid(flags[cellIndex(latticeCellOf(n), LATTICE)])) {
        highest = max(highest, max(smoke[ni], lowOrder[ni]));
        lowest = min(lowest, min(smoke[ni], lowOrder[ni]));
      }
      // The lower face is stored at this cell, the upper one at the neighbour; + along the axis.
      vec2 flux = SIXWAY_FCT_FLUX(a, side == 0 ? index : ni);
      vec2 into = side == 0 ? flux : -flux;
      in_ += max(into, 0.0);
      out_ += max(-into, 0.0);
    }
  vec2 up = highest - qtd, down = qtd - lowest;
  vec2 rPlus = mix(vec2(0.0), min(vec2(1.0), up / max(in_, 1e-30)), greaterThan(in_, vec2(0.0)));
  vec2 rMinus = mix(vec2(0.0), min(vec2(1.0), down / max(out_, 1e-30)), greaterThan(out_, vec2(0.0)));
  ratios[index] = vec4(rPlus, rMinus);
}
