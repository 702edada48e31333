#version 460
// Force of the fluid on each obstacle by momentum exchange over the bounce-back links, in the
// Galilean-invariant form of Wen et al. (2014): per link F = (c_ī − u_w) f*_ī − (c_i − u_w) f_i, with
// f_i the population the wall sends back by the rule lbm_step uses (sim_bounce_back.glsl); plus, for
// moving obstacles, the momentum of the cells that change sides (Wen et al.'s refilling term): a cell
// the obstacle covers gives it the fluid's ρu, a cell it uncovers takes ρ₀u_w from it.
// Reads the lattice as the coming lbm_step finds it (PARITY, lbm_in_place.glsl). Each subgroup adds
// its sum into the step's slot with one float atomic per component (workgroup barriers cost a
// coroutine switch per invocation on lavapipe); the order of the additions is not fixed. Only the
// cells of the obstacles' swept box run (push.boxMin/boxSize): no link to an obstacle lies outside it.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_EXT_shader_atomic_float : require
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
// As lbm_step's.
layout(constant_id = SIM_SPEC_INTERPOLATED_BOUNCE_BACK) const bool INTERPOLATED_BOUNCE_BACK = false;
layout(constant_id = SIM_SPEC_PARITY) const uint PARITY = 0u;  // the coming step's

const ivec3 SIZE = ivec3(NX, NY, NZ);

#include "linear_index.glsl"
#include "lbm_d3q19.glsl"
#include "lbm_lattice.glsl"
#include "sim_grid.glsl"

layout(std430, binding = 0) readonly buffer Params { StepParams params[]; };
layout(std430, binding = 1) readonly buffer Flags { uint flags[]; };
layout(std430, binding = 2) readonly buffer A0 { LbmPopulation a0[]; };
layout(std430, binding = 3) readonly buffer A1 { LbmPopulation a1[]; };
layout(std430, binding = 4) readonly buffer A2 { LbmPopulation a2[]; };
layout(std430, binding = 5) readonly buffer A3 { LbmPopulation a3[]; };
layout(std430, binding = 6) readonly buffer Macro_ { vec4 macro[]; };
layout(std430, binding = 7) buffer Forces { float forces[]; };  // [slot][obstacle] vec4, zeroed before
layout(push_constant) uniform Push {
  uint step;  // StepParams entry
  uint slot;  // where this step's forces go
  ivec4 boxMin;   // xyz: the first cell of the box visited
  ivec4 boxSize;  // xyz: its cells per axis
} push;

#include "lbm_in_place.glsl"

// Nothing writes the lattice in this pass: every kept population can be read where it lies.
float awayFromWall(int i, ivec3 p) { return loadKept(i, p); }

#include "sim_bounce_back.glsl"

void main() {
  uint boxCells = uint(push.boxSize.x * push.boxSize.y * push.boxSize.z);
  uint local = linearInvocationIndex();
  bool inBox = local < boxCells;
  ivec3 p = push.boxMin.xyz + cellOf(min(local, boxCells - 1u), push.boxSize.xyz);
  uint cell = cellIndex(p, SIZE);
  uint count = params[push.step].counts.x;
  uint own = inBox ? flags[cell] : 0u;
  // Cells just uncovered restart from equilibrium: their links carry no momentum this step.
  bool linked = inBox && !isSolid(own) && previousObstacleOf(own) == 0u;

  uint neighbour[Q];  // the obstacle (plus one) each population streams from, 0 for fluid
  bool wallCovers[Q];  // whether that obstacle covers the source cell now (not just a step ago)
  vec4 state = inBox ? macro[cell] : vec4(0.0);  // the previous step's velocity and density
  float rho = linked ? state.w : 0.0;
  // Covered this step: the fluid's momentum goes to the obstacle. Uncovered: the cell restarts at
  // ρ₀ = 1 and the velocity it carried as a wall (lbm_step), momentum the obstacle gives away.
  uint covered = (isSolid(own) && previousObstacleOf(own) == 0u) ? obstacleOf(own) : 0u;
  uint uncovered = (!isSolid(own) && previousObstacleOf(own) != 0u) ? previousObstacleOf(own) : 0u;
  [[unroll]] for (int i = 0; i < Q; ++i) {
    ivec3 source = wrapPeriodic(p - C[i]);  // exactly as lbm_step streams
    bool inside = all(greaterThanEqual(source, ivec3(0))) && all(lessThan(source, SIZE));
    bool near = inside && nearSolid(params[push.step], source);  // else the source is fluid
    uint sourceFlags = (linked && i > 0 && near) ? flags[cellIndex(source, SIZE)] : 0u;
    neighbour[i] = wallOf(sourceFlags);
    wallCovers[i] = isSolid(sourceFlags);
  }
  for (uint o = 0u; o < count; ++o) {
    vec3 force = vec3(0.0);
    Obstacle obstacle = params[push.step].obstacles[o];
    vec3 wall = obstacle.velocity.xyz;
    [[unroll]] for (int i = 1; i < Q; ++i) {
      if (neighbour[i] != o + 1u) continue;
      float toWall = loadKept(opposite(i), p);
      float back = bounceBack(i, p, wrapPeriodic(p - C[i]), wallCovers[i], obstacle, rho);
      force += (vec3(-C[i]) - wall) * toWall - (vec3(C[i]) - wall) * back;
    }
    if (covered == o + 1u) force += state.w * state.xyz;
    if (uncovered == o + 1u) force -= state.xyz;
    vec3 sum = subgroupAdd(force);
    if (subgroupElect() && any(notEqual(sum, vec3(0.0)))) {
      uint word = 4u * (push.slot * MAX_OBSTACLES + o);
      atomicAdd(forces[word], sum.x);
      atomicAdd(forces[word + 1u], sum.y);
      atomicAdd(forces[word + 2u], sum.z);
    }
  }
}
