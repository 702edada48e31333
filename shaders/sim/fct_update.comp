#version 460
// Flux-corrected transport, pass 3 of 3: q = q_td + the antidiffusive fluxes, each scaled by the
// limiter of the cell it leaves and the cell it enters (Zalesak 1979, eq. 13).
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

layout(std430, binding = 0) readonly buffer LowOrder { vec2 lowOrder[]; };
layout(std430, binding = 1) readonly buffer AntidiffusiveX { vec2 antidiffusiveX[]; };
layout(std430, binding = 2) readonly buffer AntidiffusiveY { vec2 antidiffusiveY[]; };
layout(std430, binding = 3) readonly buffer AntidiffusiveZ { vec2 antidiffusiveZ[]; };
layout(std430, binding = 4) readonly buffer Ratios { vec4 ratios[]; };
layout(std430, binding = 5) writeonly buffer Smoke { vec2 smoke[]; };
layout(std430, binding = 6) readonly buffer Header { uint header[]; };         // sim_bricks.glsl
layout(std430, binding = 7) readonly buffer ActiveList { uint activeList[]; };

#include "sim_fct_cell.glsl"

// The limited flux through the face between `left` and `right` (flux positive from left to right).
vec2 limited(vec2 flux, vec4 left, vec4 right) {
  vec2 positive = min(right.xy, left.zw), negative = min(left.xy, right.zw);
  return flux * mix(negative, positive, greaterThanEqual(flux, vec2(0.0)));
}

void main() {
  ivec3 s;
  if (!fctCell(s)) return;
  uint index = cellIndex(s, SMOKE);
  vec4 r = ratios[index];
  vec2 q = lowOrder[index];
  [[unroll]] for (int a = 0; a < 3; ++a) {
    ivec3 lower = s, upper = s;
    lower[a] -= 1;
    upper[a] += 1;
    if (wrapNeighbour(lower, a)) q += limited(SIXWAY_FCT_FLUX(a, index), ratios[cellIndex(lower, SMOKE)], r);
    if (wrapNeighbour(upper, a)) {
      uint ui = cellIndex(upper, SMOKE);
      q -= limited(SIXWAY_FCT_FLUX(a, ui), r, ratios[ui]);
    }
  }
  // The limiter bounds q by the local extrema (≥ 0) up to rounding; the clamp removes the last
  // −1e-7-sized rounding residue, changing the mass by no more than that.
  smoke[index] = max(q, vec2(0.0));
}
