#version 460
// One level of the Stats reduction: each workgroup summarises GROUP_SIZE * ITEMS_PER_THREAD
// consecutive inputs (floats, lengths of small vectors, or the previous level's Stats) into one Stats.
#extension GL_GOOGLE_include_directive : require
#include "stats.glsl"

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const uint ITEMS_PER_THREAD = 8;
layout(constant_id = 2) const bool FROM_STATS = false;  // input is a previous level's output
layout(constant_id = 3) const uint STRIDE = 1;          // floats from one input value to the next
layout(constant_id = 4) const uint COMPONENTS = 1;      // > 1: the value is the length of that many floats

layout(std430, binding = 0) readonly buffer Values { float values[]; };
layout(std430, binding = 1) readonly buffer StatsIn { Stats statsIn[]; };
layout(std430, binding = 2) writeonly buffer StatsOut { Stats statsOut[]; };
layout(push_constant) uniform Push { uint count; } push;

shared Stats partial[gl_WorkGroupSize.x];

float inputValue(uint i) {
  if (COMPONENTS == 1u) return values[i * STRIDE];
  float squares = 0.0;
  for (uint c = 0u; c < COMPONENTS; ++c) squares += values[i * STRIDE + c] * values[i * STRIDE + c];
  return sqrt(squares);
}

void main() {
  const uint local = gl_LocalInvocationID.x;
  const uint base = gl_WorkGroupID.x * gl_WorkGroupSize.x * ITEMS_PER_THREAD;
  Stats s = statsEmpty();
  for (uint k = 0; k < ITEMS_PER_THREAD; ++k) {
    uint i = base + k * gl_WorkGroupSize.x + local;  // strided: neighbouring threads read neighbours
    if (i >= push.count) break;
    Stats next;  // (an if, not ?:, whose mixed block/plain struct types glslang 12 miscompiles)
    if (FROM_STATS) next = statsIn[i];
    else next = statsOf(inputValue(i), i);
    s = statsCombine(s, next);
  }
  partial[local] = s;
  barrier();
  for (uint stride = gl_WorkGroupSize.x / 2; stride > 0; stride /= 2) {
    if (local < stride) partial[local] = statsCombine(partial[local], partial[local + stride]);
    barrier();
  }
  if (local == 0) statsOut[gl_WorkGroupID.x] = partial[0];
}
