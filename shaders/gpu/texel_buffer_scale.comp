#version 460
// Test kernel of the host's texel-buffer bindings: out[i] = scale * texel i of the input (read as RGBA32F
// texels through a buffer view).
layout(local_size_x = 64) in;
layout(constant_id = 0) const float SCALE = 2.0;

layout(binding = 0, rgba32f) uniform readonly imageBuffer texels;
layout(std430, binding = 1) writeonly buffer Out { vec4 values[]; };
layout(push_constant) uniform Push { uint count; } push;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i < push.count) values[i] = SCALE * imageLoad(texels, int(i));
}
