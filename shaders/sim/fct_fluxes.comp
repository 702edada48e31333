#version 460
// Flux-corrected transport of the smoke (Zalesak 1979), pass 1 of 3: for every face, the
// low-order (donor-cell) flux and the antidiffusive flux A = F_high − F_low, with Lax–Wendroff as
// the high-order flux; the low-order update q_td. Fluxes are positive along +axis, in smoke-cell
// units per substep; each cell stores the fluxes of its three lower faces.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "sim_spec.glsl"

layout(local_size_x = 16, local_size_y = 2, local_size_z = 2) in;  // one brick (sim_bricks.glsl)
layout(constant_id = SIM_SPEC_NX) const int NX = 1;
layout(constant_id = SIM_SPEC_NY) const int NY = 1;
layout(constant_id = SIM_SPEC_NZ) const int NZ = 1;
layout(constant_id = SIM_SPEC_SMOKE_UPRES) const int SMOKE_UPRES = 1;
layout(constant_id = SIM_SPEC_SPARSE) const bool SPARSE = false;
layout(constant_id = SIM_SPEC_FACE_XM) const uint FACE_XM = 0u;  // boundary type per face (sim_grid.glsl)
layout(constant_id = SIM_SPEC_FACE_XP) const uint FACE_XP = 0u;
layout(constant_id = SIM_SPEC_FACE_YM) const uint FACE_YM = 0u;
layout(constant_id = SIM_SPEC_FACE_YP) const uint FACE_YP = 0u;
layout(constant_id = SIM_SPEC_FACE_ZM) const uint FACE_ZM = 0u;
layout(constant_id = SIM_SPEC_FACE_ZP) const uint FACE_ZP = 0u;

#include "sim_grid.glsl"
#include "sim_smoke.glsl"
#include "sim_bricks.glsl"

layout(std430, binding = 0) readonly buffer Flags { uint flags[]; };
layout(std430, binding = 1) readonly buffer Macro_ { vec4 macro[]; };  // lattice velocity, cells/step
layout(std430, binding = 2) readonly buffer Smoke { vec2 smoke[]; };
layout(std430, binding = 3) writeonly buffer LowOrder { vec2 lowOrder[]; };      // q_td
layout(std430, binding = 4) writeonly buffer AntidiffusiveX { vec2 antidiffusiveX[]; };
layout(std430, binding = 5) writeonly buffer AntidiffusiveY { vec2 antidiffusiveY[]; };
layout(std430, binding = 6) writeonly buffer AntidiffusiveZ { vec2 antidiffusiveZ[]; };
layout(std430, binding = 7) readonly buffer Header { uint header[]; };         // sim_bricks.glsl
layout(std430, binding = 8) readonly buffer ActiveList { uint activeList[]; };

#include "sim_fct_cell.glsl"

#include "sim_faces.glsl"

bool solidAt(ivec3 s) { return isSolid(flags[cellIndex(latticeCellOf(s), LATTICE)]); }

// Lattice velocity at a point in lattice coordinates (cell centres at integer + 0.5), trilinear;
// across the seam on periodic axes, clamped to the outer cell centres on the others.
vec3 latticeVelocity(vec3 x) {
  ivec3 i0, i1;
  vec3 t;
  [[unroll]] for (int a = 0; a < 3; ++a) {
    float g = x[a] - 0.5;
    if (faceType(2 * a) == FACE_PERIODIC) {
      float below = floor(g);
      t[a] = g - below;
      i0[a] = (int(below) + LATTICE[a]) % LATTICE[a];
      i1[a] = (i0[a] + 1) % LATTICE[a];
    } else {
      // Scalar bounds: the validation layer of SDK 1.3.239 rejects some vector specialization-constant
      // expressions after specialization (e.g. LATTICE − 2) although spirv-val accepts them.
      g = clamp(g, 0.0, float(LATTICE[a] - 1));
      i0[a] = min(int(floor(g)), max(LATTICE[a] - 2, 0));
      i1[a] = min(i0[a] + 1, LATTICE[a] - 1);
      t[a] = g - float(i0[a]);
    }
  }
  vec3 u = vec3(0.0);
  [[unroll]] for (int k = 0; k < 8; ++k) {
    ivec3 corner = ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
    vec3 w = mix(1.0 - t, t, vec3(corner));
    u += w.x * w.y * w.z * macro[cellIndex(mix(i0, i1, bvec3(corner)), LATTICE)].xyz;
  }
  return u;
}

// Normal velocity on the lower face of smoke cell s along axis a, in smoke cells per substep
// (lattice cells per step: a substep is 1/SMOKE_UPRES of a step and a smoke cell as much smaller),
// interpolated when the smoke is finer than the lattice (with SMOKE_UPRES 1, faceFluxes averages the
// two cells' velocities it has read).
float faceVelocity(ivec3 s, int a) {
  vec3 x = (vec3(s) + 0.5) / float(SMOKE_UPRES);
  x[a] = float(s[a]) / float(SMOKE_UPRES);
  return latticeVelocity(x)[a];
}

// Velocity at the centre of smoke cell s, in smoke cells per substep.
vec3 cellVelocity(ivec3 s) {
  if (SMOKE_UPRES == 1) return macro[cellIndex(s, LATTICE)].xyz;
  return latticeVelocity((vec3(s) + 0.5) / float(SMOKE_UPRES));
}

// Fluxes through the lower (upperFace false) or upper face of smoke cell s along axis a, given the
// cell's own values, which all six faces share (q; solid; with SMOKE_UPRES 1, its velocity u in smoke
// cells per substep): each neighbour is read once (llvmpipe does not merge repeated buffer loads).
// Returns (low-order flux, antidiffusive flux) per value, + along a.
mat2 faceFluxes(ivec3 s, int a, bool upperFace, vec2 q, bool solid, vec3 u) {
  ivec3 n = s;
  n[a] += upperFace ? 1 : -1;
  uint type = faceType(2 * a + (upperFace ? 1 : 0));
  if ((n[a] < 0 || n[a] >= SMOKE[a]) && type != FACE_PERIODIC) {
    // Domain boundary: walls pass nothing; open faces let smoke out (zero gradient) and clean air in.
    if (type == FACE_NO_SLIP || type == FACE_FREE_SLIP || solid) return mat2(0.0);
    float uOut = SMOKE_UPRES == 1 ? u[a] : cellVelocity(s)[a];  // zero gradient: the cell's own velocity
    bool leaving = upperFace ? uOut > 0.0 : uOut < 0.0;
    return mat2(leaving ? uOut * q : vec2(0.0), vec2(0.0));
  }
  n[a] = (n[a] + SMOKE[a]) % SMOKE[a];  // periodic wrap
  if (solid || solidAt(n)) return mat2(0.0);  // obstacles pass no smoke
  uint neighbour = cellIndex(n, SMOKE);
  float uFace = SMOKE_UPRES == 1 ? 0.5 * (u[a] + macro[neighbour][a]) : faceVelocity(upperFace ? n : s, a);
  vec2 qN = smoke[neighbour];
  vec2 qL = upperFace ? q : qN, qR = upperFace ? qN : q;
  vec2 low = uFace > 0.0 ? uFace * qL : uFace * qR;
  vec2 high = uFace * 0.5 * (qL + qR) - 0.5 * uFace * uFace * (qR - qL);  // Lax–Wendroff
  return mat2(low, high - low);
}

void main() {
  ivec3 s;
  if (!fctCell(s)) return;
  uint index = cellIndex(s, SMOKE);
  vec2 q = smoke[index], qtd = q;
  bool solid = solidAt(s);
  vec3 u = SMOKE_UPRES == 1 ? cellVelocity(s) : vec3(0.0);  // finer grids interpolate per face
  [[unroll]] for (int a = 0; a < 3; ++a) {
    mat2 lowerFace = faceFluxes(s, a, false, q, solid, u);
    mat2 upperFace = faceFluxes(s, a, true, q, solid, u);
    qtd += lowerFace[0] - upperFace[0];
    if (a == 0) antidiffusiveX[index] = lowerFace[1];  // sim_fct_fluxes.glsl
    else if (a == 1) antidiffusiveY[index] = lowerFace[1];
    else antidiffusiveZ[index] = lowerFace[1];
  }
  lowOrder[index] = qtd;
}
