#version 460
// Bilinear upsampling by an integer factor, as torch.nn.functional.interpolate(mode="bilinear",
// align_corners=False): source coordinate (dst + 0.5) / factor - 0.5, clamped at 0, neighbours clamped at the
// last pixel. One invocation: one output pixel, all channel groups.
#extension GL_GOOGLE_include_directive : require
#ifdef NN_FP16
#extension GL_EXT_shader_16bit_storage : require
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require
#endif
#extension GL_EXT_control_flow_attributes : require
#include "nn_spec.glsl"
#include "nn_tensor.glsl"

layout(local_size_x_id = NN_SPEC_LOCAL_SIZE_X, local_size_y_id = NN_SPEC_LOCAL_SIZE_Y) in;
layout(constant_id = NN_SPEC_IN_WIDTH) const int IN_WIDTH = 1;
layout(constant_id = NN_SPEC_IN_HEIGHT) const int IN_HEIGHT = 1;
layout(constant_id = NN_SPEC_GROUPS) const int GROUPS = 1;
layout(constant_id = NN_SPEC_FACTOR) const int FACTOR = 2;

NN_INPUT_MAP(0, inputMap);
NN_OUTPUT_MAP(1, outputMap);

// The lower source index along one axis and the weight of the upper one.
void sourceOf(int dst, int size, out int lower, out int upper, out float lambda) {
  const float source = max((float(dst) + 0.5) / float(FACTOR) - 0.5, 0.0);
  lower = int(source);
  upper = min(lower + 1, size - 1);
  lambda = source - float(lower);
}

void main() {
  const ivec2 dst = ivec2(gl_GlobalInvocationID.xy);
  if (dst.x >= IN_WIDTH * FACTOR || dst.y >= IN_HEIGHT * FACTOR) return;
  int x0, x1, y0, y1;
  float lx, ly;
  sourceOf(dst.x, IN_WIDTH, x0, x1, lx);
  sourceOf(dst.y, IN_HEIGHT, y0, y1, ly);
  [[unroll]] for (int g = 0; g < GROUPS; ++g) {
    const vec4 top = mix(imageLoad(inputMap, nnIndex(x0, y0, g, IN_WIDTH, IN_HEIGHT)),
                         imageLoad(inputMap, nnIndex(x1, y0, g, IN_WIDTH, IN_HEIGHT)), lx);
    const vec4 bottom = mix(imageLoad(inputMap, nnIndex(x0, y1, g, IN_WIDTH, IN_HEIGHT)),
                            imageLoad(inputMap, nnIndex(x1, y1, g, IN_WIDTH, IN_HEIGHT)), lx);
    outputMap[nnIndex(dst.x, dst.y, g, IN_WIDTH * FACTOR, IN_HEIGHT * FACTOR)] = NN_TEXEL(mix(top, bottom, ly));
  }
}
