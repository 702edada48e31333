#version 460
// NAFBlock, first kernel (NAFNet, Chen et al. 2022): LayerNorm2d of the block input, then the 1x1 conv1 that
// expands C channels to 2G (G = GATED_CHANNELS, C * dw_expand / 2). The outputs are stored in SimpleGate order:
// groups [0, GATED_GROUPS) hold channels [0, G) and groups [GATED_GROUPS, 2 GATED_GROUPS) hold [G, 2G), each
// half padded to whole groups, so the gate multiplies group g by group g + GATED_GROUPS.
// One invocation: PX pixels along x, all output groups.
#extension GL_GOOGLE_include_directive : require
#ifdef NN_FP16
#extension GL_EXT_shader_16bit_storage : require
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require
#endif
#extension GL_EXT_control_flow_attributes : require
#include "nn_spec.glsl"
#include "nn_tensor.glsl"

layout(local_size_x_id = NN_SPEC_LOCAL_SIZE_X, local_size_y_id = NN_SPEC_LOCAL_SIZE_Y) in;
layout(constant_id = NN_SPEC_WIDTH) const int WIDTH = 1;
layout(constant_id = NN_SPEC_HEIGHT) const int HEIGHT = 1;
layout(constant_id = NN_SPEC_CHANNELS) const int CHANNELS = 4;
layout(constant_id = NN_SPEC_GATED_CHANNELS) const int GATED_CHANNELS = 4;
layout(constant_id = NN_SPEC_PX) const int PX = 1;
layout(constant_id = NN_SPEC_EPS) const float EPS = 1e-6;

const int GROUPS = (CHANNELS + 3) / 4;
const int OUT_GROUPS = 2 * ((GATED_CHANNELS + 3) / 4);
#define NN_LN_GROUPS GROUPS
#define NN_LN_CHANNELS CHANNELS
#include "nn_layer_norm.glsl"

// LayerNorm weight [GROUPS], bias [GROUPS]; then per output group: [input channel] vec4 weights, bias.
const int OUT_VEC4S = GROUPS * 4 + 1;
layout(binding = 0) uniform Weights { vec4 weights[2 * GROUPS + OUT_GROUPS * OUT_VEC4S]; };
NN_INPUT_MAP(1, inputMap);
NN_OUTPUT_MAP(2, outputMap);

vec4 normed[PX][GROUPS];  // LayerNorm2d of the input, scaled and shifted

// Output group o of conv1 over the PX pixels at (x0, y).
void expandGroup(int o, int x0, int y) {
  const int base = 2 * GROUPS + o * OUT_VEC4S;
  vec4 acc[PX];
  [[unroll]] for (int p = 0; p < PX; ++p) acc[p] = weights[base + OUT_VEC4S - 1];
  [[unroll]] for (int g = 0; g < GROUPS; ++g)
    [[unroll]] for (int c = 0; c < 4; ++c) {
      const vec4 w = weights[base + g * 4 + c];
      [[unroll]] for (int p = 0; p < PX; ++p) acc[p] += normed[p][g][c] * w;
    }
  [[unroll]] for (int p = 0; p < PX; ++p)
    if (x0 + p < WIDTH) outputMap[nnIndex(x0 + p, y, o, WIDTH, HEIGHT)] = NN_TEXEL(acc[p]);
}

void main() {
  const int x0 = int(gl_GlobalInvocationID.x) * PX;
  const int y = int(gl_GlobalInvocationID.y);
  if (x0 >= WIDTH || y >= HEIGHT) return;
  [[unroll]] for (int p = 0; p < PX; ++p) {
    vec4 x[GROUPS];
    [[unroll]] for (int g = 0; g < GROUPS; ++g) x[g] = imageLoad(inputMap, nnIndex(x0 + p, y, g, WIDTH, HEIGHT));
    nnLayerNorm(x, EPS);
    [[unroll]] for (int g = 0; g < GROUPS; ++g) normed[p][g] = x[g] * weights[g] + weights[GROUPS + g];
  }
  // Small blocks unroll the loop over output groups, wide ones loop (nn_tensor.glsl, NN_UNROLLED_GROUPS).
  if (OUT_GROUPS <= 2 * NN_UNROLLED_GROUPS) {
    [[unroll]] for (int o = 0; o < OUT_GROUPS; ++o) expandGroup(o, x0, y);
  } else {
    [[dont_unroll]] for (int o = 0; o < OUT_GROUPS; ++o) expandGroup(o, x0, y);
  }
}
