#version 460
// The sparse smoke transport's activity (sim_bricks.glsl), once per substep before the FCT passes: a brick is
// active when a value of its cells or of the cells around it (one cell wide) exceeds SPARSE_THRESHOLD, so that
// every value the FCT's stencil reads from outside the active bricks is at most the threshold. Appends each active
// brick to the active list and each brick that was active in the last substep but is not now to the clear list,
// with the lists' indirect dispatches.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "sim_spec.glsl"

layout(local_size_x = 64) in;
layout(constant_id = SIM_SPEC_NX) const int NX = 1;
layout(constant_id = SIM_SPEC_NY) const int NY = 1;
layout(constant_id = SIM_SPEC_NZ) const int NZ = 1;
layout(constant_id = SIM_SPEC_SMOKE_UPRES) const int SMOKE_UPRES = 1;
layout(constant_id = SIM_SPEC_PERIODIC_X) const bool PERIODIC_X = false;
layout(constant_id = SIM_SPEC_PERIODIC_Y) const bool PERIODIC_Y = false;
layout(constant_id = SIM_SPEC_PERIODIC_Z) const bool PERIODIC_Z = false;
layout(constant_id = SIM_SPEC_SPARSE_THRESHOLD) const float SPARSE_THRESHOLD = 0.0;

#include "linear_index.glsl"
#include "sim_grid.glsl"
#include "sim_smoke.glsl"
#include "sim_bricks.glsl"

layout(std430, binding = 0) readonly buffer Smoke { vec2 smoke[]; };
layout(std430, binding = 1) buffer Activity { uint activity[]; };  // per brick: BRICK_ACTIVE last substep
layout(std430, binding = 2) buffer Header { uint header[]; };
layout(std430, binding = 3) writeonly buffer ActiveList { uint activeList[]; };
layout(std430, binding = 4) writeonly buffer ClearList { uint clearList[]; };

bool periodic(int a) { return a == 0 ? PERIODIC_X : (a == 1 ? PERIODIC_Y : PERIODIC_Z); }

// A new entry of the list whose dispatch starts at header word `dispatch`, its length at word `count`.
uint append(uint dispatch, uint count) {
  uint entry = atomicAdd(header[count], 1u);
  atomicMax(header[dispatch], min(entry + 1u, BRICK_LIST_ROW));
  atomicMax(header[dispatch + 1u], entry / BRICK_LIST_ROW + 1u);
  atomicMax(header[dispatch + 2u], 1u);
  return entry;
}

void main() {
  uint brick = linearInvocationIndex();
  if (brick >= BRICK_COUNT) return;
  ivec3 lo = brickOrigin(brick) - 1, hi = min(brickOrigin(brick) + BRICK, SMOKE) + 1;
  [[unroll]] for (int a = 0; a < 3; ++a)
    if (!periodic(a)) {  // on a periodic axis the border wraps around
      lo[a] = max(lo[a], 0);
      hi[a] = min(hi[a], SMOKE[a]);
    }
  bool busy = false;  // ("active" is a reserved word in GLSL)
  for (int z = lo.z; z < hi.z && !busy; ++z)
    for (int y = lo.y; y < hi.y && !busy; ++y)
      for (int x = lo.x; x < hi.x && !busy; ++x) {
        ivec3 c = ivec3(x, y, z);
        [[unroll]] for (int a = 0; a < 3; ++a) c[a] = (c[a] + SMOKE[a]) % SMOKE[a];
        busy = any(greaterThan(smoke[cellIndex(c, SMOKE)], vec2(SPARSE_THRESHOLD)));
      }
  bool was = (activity[brick] & BRICK_ACTIVE) != 0u;
  activity[brick] = busy ? BRICK_ACTIVE : 0u;
  if (busy) activeList[append(HEADER_ACTIVE_DISPATCH, HEADER_ACTIVE_COUNT)] = brick;
  else if (was) clearList[append(HEADER_CLEAR_DISPATCH, HEADER_CLEAR_COUNT)] = brick;
}
