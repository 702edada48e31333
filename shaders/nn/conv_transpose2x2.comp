#version 460
// ConvTranspose2d of PyTorch with kernel 2 and stride 2 (the UNet's learnt upsampling): input pixel (x, y)
// alone makes output pixels (2x + dx, 2y + dy). One invocation: PX input pixels along x, for one output
// channel group (the workgroup's z index, as in conv2d.comp).
#extension GL_GOOGLE_include_directive : require
#ifdef NN_FP16
#extension GL_EXT_shader_16bit_storage : require
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require
#endif
#extension GL_EXT_control_flow_attributes : require
#include "nn_spec.glsl"
#include "nn_activation.glsl"
#include "nn_tensor.glsl"

layout(local_size_x_id = NN_SPEC_LOCAL_SIZE_X, local_size_y_id = NN_SPEC_LOCAL_SIZE_Y) in;
layout(constant_id = NN_SPEC_IN_WIDTH) const int IN_WIDTH = 1;
layout(constant_id = NN_SPEC_IN_HEIGHT) const int IN_HEIGHT = 1;
layout(constant_id = NN_SPEC_GROUPS_IN) const int GROUPS_IN = 1;
layout(constant_id = NN_SPEC_PX) const int PX = 2;
layout(constant_id = NN_SPEC_ACTIVATION) const int ACTIVATION = NN_ACT_NONE;
layout(constant_id = NN_SPEC_NEGATIVE_SLOPE) const float NEGATIVE_SLOPE = 0.0;
layout(constant_id = NN_SPEC_WEIGHT_VEC4S) const int WEIGHT_VEC4S = 1;

// Per output group: weights [input channel][dy][dx] as vec4 over the group's 4 output channels, then bias.
const int GROUP_VEC4S = GROUPS_IN * 4 * 4 + 1;

NN_INPUT_MAP(0, inputMap);
layout(binding = 1) uniform Weights { vec4 weights[WEIGHT_VEC4S]; };
NN_OUTPUT_MAP(2, outputMap);
layout(push_constant) uniform Push {
  int firstGroup;  // the output group of the chunk's first (workgroup z = 0)
} push;

void main() {
  const int x0 = int(gl_GlobalInvocationID.x) * PX;
  const int y = int(gl_GlobalInvocationID.y);
  if (x0 >= IN_WIDTH || y >= IN_HEIGHT) return;
  const int base = int(gl_WorkGroupID.z) * GROUP_VEC4S;

  vec4 acc[PX][4];  // [pixel][dy * 2 + dx]
  [[unroll]] for (int p = 0; p < PX; ++p)
    [[unroll]] for (int k = 0; k < 4; ++k) acc[p][k] = weights[base + GROUP_VEC4S - 1];
  [[unroll]] for (int g = 0; g < GROUPS_IN; ++g) {
    vec4 v[PX];
    [[unroll]] for (int p = 0; p < PX; ++p) v[p] = imageLoad(inputMap, nnIndex(x0 + p, y, g, IN_WIDTH, IN_HEIGHT));
    [[unroll]] for (int c = 0; c < 4; ++c)
      [[unroll]] for (int k = 0; k < 4; ++k) {
        const vec4 w = weights[base + (g * 4 + c) * 4 + k];
        [[unroll]] for (int p = 0; p < PX; ++p) acc[p][k] += v[p][c] * w;
      }
  }
  const int outGroup = push.firstGroup + int(gl_WorkGroupID.z);
  [[unroll]] for (int p = 0; p < PX; ++p)
    if (x0 + p < IN_WIDTH)
      [[unroll]] for (int k = 0; k < 4; ++k)
        outputMap[nnIndex(2 * (x0 + p) + (k & 1), 2 * y + (k >> 1), outGroup, 2 * IN_WIDTH, 2 * IN_HEIGHT)] =
            NN_TEXEL(nnActivate(acc[p][k], ACTIVATION, NEGATIVE_SLOPE));
}
