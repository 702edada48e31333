#version 460
// The sparse smoke transport (sim_bricks.glsl), after the activity pass: the bricks that turned inactive drop
// their smoke (at most the threshold; exactly zero for a threshold of 0) and the FCT values they computed in the
// last substep, which the FCT passes of their active neighbours read as those of clean air.
#extension GL_GOOGLE_include_directive : require
#include "sim_spec.glsl"

layout(local_size_x = 16, local_size_y = 2, local_size_z = 2) in;  // one brick
layout(constant_id = SIM_SPEC_NX) const int NX = 1;
layout(constant_id = SIM_SPEC_NY) const int NY = 1;
layout(constant_id = SIM_SPEC_NZ) const int NZ = 1;
layout(constant_id = SIM_SPEC_SMOKE_UPRES) const int SMOKE_UPRES = 1;

#include "sim_grid.glsl"
#include "sim_smoke.glsl"
#include "sim_bricks.glsl"

layout(std430, binding = 0) readonly buffer Header { uint header[]; };
layout(std430, binding = 1) readonly buffer ClearList { uint clearList[]; };
layout(std430, binding = 2) writeonly buffer Smoke { vec2 smoke[]; };
layout(std430, binding = 3) writeonly buffer LowOrder { vec2 lowOrder[]; };
layout(std430, binding = 4) writeonly buffer AntidiffusiveX { vec2 antidiffusiveX[]; };
layout(std430, binding = 5) writeonly buffer AntidiffusiveY { vec2 antidiffusiveY[]; };
layout(std430, binding = 6) writeonly buffer AntidiffusiveZ { vec2 antidiffusiveZ[]; };
layout(std430, binding = 7) writeonly buffer Ratios { vec4 ratios[]; };

void main() {
  uint entry = brickListIndex();
  if (entry >= header[HEADER_CLEAR_COUNT]) return;
  ivec3 s = brickOrigin(clearList[entry]) + ivec3(gl_LocalInvocationID);
  if (s.x >= SMOKE.x || s.y >= SMOKE.y || s.z >= SMOKE.z) return;
  uint index = cellIndex(s, SMOKE);
  smoke[index] = vec2(0.0);
  lowOrder[index] = vec2(0.0);
  antidiffusiveX[index] = vec2(0.0);
  antidiffusiveY[index] = vec2(0.0);
  antidiffusiveZ[index] = vec2(0.0);
  ratios[index] = vec4(0.0);
}
