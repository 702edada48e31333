#version 460
// One lattice Boltzmann step per fluid cell, in place (lbm_in_place.glsl: steps of parity 0 pull from and push
// into the neighbours, steps of parity 1 stay in the cell): streaming with the boundary conditions,
// regularized collision with Smagorinsky and Guo forcing (lbm_d3q19.glsl), and the cell's velocity and density
// into `macro` for the smoke and the watchdog.
// Pipelines of this shader share the cells (BOUNDARY_CELLS): the interior, which pulls every population
// from a fixed offset, and the cells next to a face or an obstacle, which need the boundary conditions.
// llvmpipe runs the code of a branch in every SIMD group whether or not a lane takes it, so keeping the
// boundary code out of the interior dispatch makes the LBM pass 1.5–2.2× faster there (docs/benchmarks.md).
// For the same reason the boundary cells come in two pipelines when the obstacles' box stays off the domain's
// faces (BOUNDARY_FACES: the face slabs, without bounce-back code; BOUNDARY_OBSTACLES: the box, without the
// face conditions), and in one with both codes when it reaches a face. The cells a moving obstacle uncovered
// this step come last, in a pipeline of their own (UNCOVERED_CELLS): they restart from equilibrium and so read
// nothing, but their slots hold what their neighbours sent towards the wall, which the neighbours read back
// in this step (lbm_in_place.glsl).
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
layout(constant_id = SIM_SPEC_TAU0) const float TAU0 = 0.6;                // from the molecular viscosity
layout(constant_id = SIM_SPEC_SMAGORINSKY) const float SMAGORINSKY = 0.0;  // LES constant C_s
// Smoke cells per lattice cell per axis.
layout(constant_id = SIM_SPEC_SMOKE_UPRES) const int SMOKE_UPRES = 1;
// Lattice acceleration per unit temperature and per unit smoke density.
layout(constant_id = SIM_SPEC_BUOYANCY_T) const float BUOYANCY_T = 0.0;
layout(constant_id = SIM_SPEC_BUOYANCY_D) const float BUOYANCY_D = 0.0;
layout(constant_id = SIM_SPEC_UP_X) const float UP_X = 0.0;      // unit vector against gravity
layout(constant_id = SIM_SPEC_UP_Y) const float UP_Y = 1.0;
layout(constant_id = SIM_SPEC_UP_Z) const float UP_Z = 0.0;
layout(constant_id = SIM_SPEC_BODY_X) const float BODY_X = 0.0;  // constant lattice acceleration
layout(constant_id = SIM_SPEC_BODY_Y) const float BODY_Y = 0.0;
layout(constant_id = SIM_SPEC_BODY_Z) const float BODY_Z = 0.0;
layout(constant_id = SIM_SPEC_WIND_X) const float WIND_X = 0.0;  // lattice velocity on inflow faces
layout(constant_id = SIM_SPEC_WIND_Y) const float WIND_Y = 0.0;
layout(constant_id = SIM_SPEC_WIND_Z) const float WIND_Z = 0.0;
layout(constant_id = SIM_SPEC_PARABOLIC_INFLOW) const bool PARABOLIC_INFLOW = false;
// Obstacles (sim_bounce_back.glsl).
layout(constant_id = SIM_SPEC_INTERPOLATED_BOUNCE_BACK) const bool INTERPOLATED_BOUNCE_BACK = false;
// This pipeline's cells (cellVisited).
layout(constant_id = SIM_SPEC_BOUNDARY_CELLS) const bool BOUNDARY_CELLS = false;
layout(constant_id = SIM_SPEC_BOUNDARY_FACES) const bool BOUNDARY_FACES = true;          // boundary pipelines:
layout(constant_id = SIM_SPEC_BOUNDARY_OBSTACLES) const bool BOUNDARY_OBSTACLES = true;  // which cells and code
layout(constant_id = SIM_SPEC_UNCOVERED_CELLS) const bool UNCOVERED_CELLS = false;
layout(constant_id = SIM_SPEC_PARITY) const uint PARITY = 0u;  // lbm_in_place.glsl

const uint CELLS = uint(NX * NY * NZ);
const ivec3 SIZE = ivec3(NX, NY, NZ);

#include "linear_index.glsl"
#include "lbm_d3q19.glsl"
#include "lbm_lattice.glsl"
#include "sim_grid.glsl"

layout(std430, binding = 0) readonly buffer Params { StepParams params[]; };
layout(std430, binding = 1) readonly buffer Flags { uint flags[]; };
layout(std430, binding = 2) buffer A0 { LbmPopulation a0[]; };
layout(std430, binding = 3) buffer A1 { LbmPopulation a1[]; };
layout(std430, binding = 4) buffer A2 { LbmPopulation a2[]; };
layout(std430, binding = 5) buffer A3 { LbmPopulation a3[]; };
layout(std430, binding = 6) buffer Macro_ { vec4 macro[]; };  // xyz velocity, w density
layout(std430, binding = 7) readonly buffer Smoke { vec2 smoke[]; };  // density, temperature
// The box cells' populations sent in the step before, as stored (lbm_keep_away.comp).
layout(std430, binding = 8) readonly buffer W0 { LbmPopulation w0[]; };
layout(std430, binding = 9) readonly buffer W1 { LbmPopulation w1[]; };
layout(std430, binding = 10) readonly buffer W2 { LbmPopulation w2[]; };
layout(std430, binding = 11) readonly buffer W3 { LbmPopulation w3[]; };
layout(push_constant) uniform Push {
  uint step;
  uint unused[3];
  ivec4 boxMin;   // xyz: the obstacles' swept box (ObstacleSet::sweptBox), where nearSolid cells lie
  ivec4 boxSize;  // xyz: its cells per axis
} push;

#include "lbm_in_place.glsl"

// Interpolated bounce-back (q > ½): the cell next to the wall lies in the obstacles' box.
float awayFromWall(int i, ivec3 p) {
  uint boxCells = uint(push.boxSize.x * push.boxSize.y * push.boxSize.z);
  uint word = uint(i % POPULATIONS_PER_BUFFER) * boxCells + cellIndex(p - push.boxMin.xyz, push.boxSize.xyz);
  return decodePopulation(i, SIXWAY_RAW(i, word, w0, w1, w2, w3));
}

#include "sim_bounce_back.glsl"

// f*_j of cell p, this step's result, kept where the next step (the other parity) looks for it.
void storeKept(int j, ivec3 p, float value) {
  Slot s = keptSlot(j, p, 1u - PARITY);
  SIXWAY_STORE(s.population, s.cell, value, a0, a1, a2, a3)
}

vec3 inflowVelocity(ivec3 p, int normalAxis) {
  vec3 u = vec3(WIND_X, WIND_Y, WIND_Z);
  if (!PARABOLIC_INFLOW) return u;
  [[unroll]] for (int b = 0; b < 3; ++b) {  // 4s(1 − s) across each channel bounded by no-slip walls
    if (b == normalAxis || faceType(2 * b) != FACE_NO_SLIP || faceType(2 * b + 1) != FACE_NO_SLIP) continue;
    float s = (float(p[b]) + 0.5) / float(SIZE[b]);
    u *= 4.0 * s * (1.0 - s);
  }
  return u;
}

// The population arriving at fluid cell p along C[i] from a neighbour outside the domain.
float fromOutside(int i, ivec3 p, ivec3 source, vec4 previous) {
  float bounceBack = loadKept(opposite(i), p);  // a wall at rest, half-way between the cells
  int outAxes = 0, axis = 0;
  bool wall = false, inflow = false;
  [[unroll]] for (int a = 0; a < 3; ++a) {
    if (source[a] >= 0 && source[a] < SIZE[a]) continue;
    uint type = faceType(2 * a + (source[a] < 0 ? 0 : 1));
    ++outAxes;
    axis = a;
    wall = wall || type == FACE_NO_SLIP || type == FACE_FREE_SLIP;
    inflow = inflow || type == FACE_INFLOW;
  }
  if (wall) {
    uint type = faceType(2 * axis + (source[axis] < 0 ? 0 : 1));
    if (type != FACE_FREE_SLIP || outAxes > 1) return bounceBack;
    // Specular reflection: the population left a tangential neighbour with its normal component flipped.
    ivec3 mirrored = C[i];
    mirrored[axis] = -mirrored[axis];
    ivec3 from = source;  // already wrapped on periodic axes
    from[axis] = p[axis];
    int r = 0;
    [[unroll]] for (int j = 1; j < Q; ++j) if (C[j] == mirrored) r = j;
    if (any(lessThan(from, ivec3(0))) || any(greaterThanEqual(from, SIZE))) return bounceBack;
    uint fromCell = cellIndex(from, SIZE);
    if (wallOf(flags[fromCell]) != 0u) return bounceBack;
    return loadKept(r, from);
  }
  // Inflow: a wall moving at the inflow velocity, half-way outside (Ladd 1994), second order like
  // the obstacles' bounce-back; an equilibrium inflow falls a few percent short of the set velocity.
  if (inflow) return bounceBack + 6.0 * W[i] * previous.w * dot(vec3(C[i]), inflowVelocity(p, axis));
  // Outflow: ambient pressure and the cell's own velocity without its component back into the domain. With
  // it, a cell whose flow turned inward received populations that pushed further inward: the backflow fed
  // itself (plume tripped the watchdog at step 1520 at the z+ face by the floor).
  vec3 u = previous.xyz;
  [[unroll]] for (int a = 0; a < 3; ++a) {
    if (source[a] < 0) u[a] = min(u[a], 0.0);
    if (source[a] >= SIZE[a]) u[a] = max(u[a], 0.0);
  }
  return equilibrium(i, 1.0, u);
}

vec3 bodyForce(ivec3 p, float rho) {
  vec2 s = vec2(0.0);
  for (int z = 0; z < SMOKE_UPRES; ++z)
    for (int y = 0; y < SMOKE_UPRES; ++y)
      for (int x = 0; x < SMOKE_UPRES; ++x)
        s += smoke[cellIndex(p * SMOKE_UPRES + ivec3(x, y, z), SIZE * SMOKE_UPRES)];
  s /= float(SMOKE_UPRES * SMOKE_UPRES * SMOKE_UPRES);
  vec3 a = (BUOYANCY_T * s.y + BUOYANCY_D * s.x) * vec3(UP_X, UP_Y, UP_Z) + vec3(BODY_X, BODY_Y, BODY_Z);
  return rho * a;
}

// An axis one cell deep between periodic faces (a quasi-2D run) wraps every link back onto the cell itself:
// it has no boundary cells.
bvec3 oneCellPeriodic() {
  return bvec3(NX == 1 && FACE_XM == FACE_PERIODIC, NY == 1 && FACE_YM == FACE_PERIODIC,
               NZ == 1 && FACE_ZM == FACE_PERIODIC);
}
ivec3 innerMin() { return ivec3(not(oneCellPeriodic())); }  // the interior: [innerMin, SIZE − innerMin)
ivec3 innerSize() { return max(SIZE - 2 * innerMin(), ivec3(0)); }

// Stored cells from a cell to its neighbour along C[i]; 0 along an axis one cell deep between periodic faces.
int neighbourOffset(int i) {
  ivec3 c = mix(C[i], ivec3(0), oneCellPeriodic());
  return c.x + STORED.x * (c.y + STORED.y * c.z);
}

// The interior's cells store at fixed offsets; the boundary cells' neighbours may wrap or be ghosts.
void storeCollided(int i, ivec3 p, uint stored, float value) {
  if (BOUNDARY_CELLS) {
    storeKept(i, p, value);
  } else if (PARITY == 0u) {
    SIXWAY_STORE(i, uint(int(stored) + neighbourOffset(i)), value, a0, a1, a2, a3)
  } else {
    SIXWAY_STORE(opposite(i), stored, value, a0, a1, a2, a3)
  }
}

bool onShell(ivec3 p) { return any(lessThan(p, innerMin())) || any(greaterThanEqual(p, SIZE - innerMin())); }
bool inSweptBox(ivec3 p) {
  return all(greaterThanEqual(p, push.boxMin.xyz)) && all(lessThan(p, push.boxMin.xyz + push.boxSize.xyz));
}

// Cells of the face slabs across `axis`: both sides, one where the axis is one cell deep, none if periodic so.
uint slabCells(int axis) {
  if (oneCellPeriodic()[axis]) return 0u;
  return (CELLS / uint(SIZE[axis])) * (SIZE[axis] > 1 ? 2u : 1u);
}

// The cell that invocation `index` updates, or −1 for none. Interior pipeline: the interior box less the
// cells next to an obstacle (nearSolid, inside the swept box). Boundary pipelines: the face slabs across x,
// y, z (a cell on two faces counted by the first; BOUNDARY_FACES), then the swept box's cells off the faces
// next to an obstacle this step (BOUNDARY_OBSTACLES). Uncovered pipeline: the swept box's cells (main() keeps
// the uncovered ones).
int cellVisited(uint index) {
  uint boxCells = uint(push.boxSize.x * push.boxSize.y * push.boxSize.z);
  if (UNCOVERED_CELLS)
    return index < boxCells ? int(cellIndex(push.boxMin.xyz + cellOf(index, push.boxSize.xyz), SIZE)) : -1;
  if (!BOUNDARY_CELLS) {
    ivec3 inner = innerSize();
    if (index >= uint(inner.x * inner.y * inner.z)) return -1;
    ivec3 p = innerMin() + cellOf(index, inner);
    return nearSolid(params[push.step], p) && inSweptBox(p) ? -1 : int(cellIndex(p, SIZE));
  }
  [[unroll]] for (int a = 0; a < 3; ++a) {
    uint cells = BOUNDARY_FACES ? slabCells(a) : 0u;
    if (index < cells) {
      int u = a == 0 ? 1 : 0, v = a == 2 ? 1 : 2;  // the slab's two axes
      uint perSide = CELLS / uint(SIZE[a]);
      uint j = index % perSide;
      ivec3 p = ivec3(0);
      p[u] = int(j % uint(SIZE[u]));
      p[v] = int(j / uint(SIZE[u]));
      p[a] = index < perSide ? 0 : SIZE[a] - 1;
      for (int b = 0; b < a; ++b)
        if (!oneCellPeriodic()[b] && (p[b] == 0 || p[b] == SIZE[b] - 1)) return -1;
      return int(cellIndex(p, SIZE));
    }
    index -= cells;
  }
  if (!BOUNDARY_OBSTACLES || index >= boxCells) return -1;
  ivec3 p = push.boxMin.xyz + cellOf(index, push.boxSize.xyz);
  return !onShell(p) && nearSolid(params[push.step], p) ? int(cellIndex(p, SIZE)) : -1;
}

void main() {
  int visited = cellVisited(linearInvocationIndex());
  if (visited < 0) return;
  uint cell = uint(visited);
  ivec3 p = cellOf(cell, SIZE);
  uint flag = flags[cell];
  // Uncovered by a moving obstacle this step: the last pipeline's cells, and only its.
  bool uncovered = BOUNDARY_CELLS && BOUNDARY_OBSTACLES && !isSolid(flag) && previousObstacleOf(flag) != 0u;
  if (uncovered != UNCOVERED_CELLS) return;
  vec4 previous = macro[cell];
  if (isSolid(flag)) {  // obstacles move rigidly; their cells carry the wall velocity
    macro[cell] = vec4(params[push.step].obstacles[obstacleOf(flag) - 1u].velocity.xyz, 1.0);
    return;
  }

  float f[Q];
  uint stored = storedCell(p);
  if (!BOUNDARY_CELLS) {  // no face and no obstacle among the neighbours: fixed offsets
    [[unroll]] for (int i = 0; i < Q; ++i) {
      f[i] = PARITY == 0u ? SIXWAY_LOAD(opposite(i), uint(int(stored) - neighbourOffset(i)), a0, a1, a2, a3)
                          : SIXWAY_LOAD(i, stored, a0, a1, a2, a3);
    }
  } else if (UNCOVERED_CELLS) {  // start from equilibrium at the wall's velocity
    [[unroll]] for (int i = 0; i < Q; ++i) f[i] = equilibrium(i, 1.0, previous.xyz);
  } else {
    [[unroll]] for (int i = 0; i < Q; ++i) {
      ivec3 source = wrapPeriodic(p - C[i]);
      if (BOUNDARY_FACES && (any(lessThan(source, ivec3(0))) || any(greaterThanEqual(source, SIZE)))) {
        f[i] = fromOutside(i, p, source, previous);
        continue;
      }
      // Outside the obstacles' box no cell is or was solid: no flags to read (the box holds wrapped cells).
      uint sourceFlags =
          BOUNDARY_OBSTACLES && nearSolid(params[push.step], source) ? flags[cellIndex(source, SIZE)] : 0u;
      uint wallIndex = wallOf(sourceFlags);
      if (wallIndex != 0u) {
        Obstacle wall = params[push.step].obstacles[wallIndex - 1u];
        f[i] = bounceBack(i, p, source, isSolid(sourceFlags), wall, previous.w);
      } else {
        f[i] = loadKept(i, source);
      }
    }
  }

  // The force needs the density, the density needs no force: take ρ first.
  float rho = 0.0;
  [[unroll]] for (int i = 0; i < Q; ++i) rho += f[i];
  vec3 force = bodyForce(p, rho);
  Macro m = moments(f, force);
  float tau = effectiveTau(TAU0, SMAGORINSKY, m, force);

  // A velocity inlet sets the populations to equilibrium at the inflow velocity. One store loop for both
  // kinds of cell: llvmpipe runs both sides of a branch, and a second loop of 19 masked stores costs more
  // than the inlet's equilibria computed beside every cell's collision.
  uint inlet = inletOf(flag);
  bool setsFlow = false;
  vec3 inflow = vec3(0.0);
  if (inlet != 0u) {
    Inlet in_ = params[push.step].inlets[inlet - 1u];
    setsFlow = inletSetsFlow(in_);
    inflow = in_.velocity.xyz + in_.velocity.w * length(in_.velocity.xyz) * noise3(p, params[push.step].counts.z);
  }
  [[unroll]] for (int i = 0; i < Q; ++i)
    storeCollided(i, p, stored, setsFlow ? equilibrium(i, m.rho, inflow) : collide(i, m, tau, force));
  macro[cell] = vec4(setsFlow ? inflow : m.u, m.rho);
}
