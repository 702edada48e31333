#version 460
// A plain copy through the shader cores, 16 bytes per invocation: the bandwidth a memory-bound kernel can
// reach on a device whose vkCmdCopyBuffer is slower (NVIDIA's ran at a quarter of what the LBM's
// streaming-only kernel moved; docs/gpu.md). Used by gpu::measureCopyBandwidth.
#extension GL_GOOGLE_include_directive : require
#include "linear_index.glsl"

layout(local_size_x = 256) in;
layout(std430, binding = 0) readonly buffer Source { uvec4 source[]; };
layout(std430, binding = 1) writeonly buffer Destination { uvec4 destination[]; };
layout(push_constant) uniform Push { uint count; } push;

void main() {
  uint index = linearInvocationIndex();
  if (index < push.count) destination[index] = source[index];
}
