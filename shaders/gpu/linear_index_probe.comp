#version 460
// Test of gpu::Sequence::dispatchLinear (tests/gpu/test_dispatch_linear.cpp): every invocation below the
// count adds its index + 1 to its own slot, so a slot visited twice, never, or by the wrong index shows.
#extension GL_GOOGLE_include_directive : require
#include "linear_index.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Slots { uint slots[]; };
layout(push_constant) uniform Push { uint count; } push;

void main() {
  uint index = linearInvocationIndex();
  if (index < push.count) slots[index] += index + 1u;
}
