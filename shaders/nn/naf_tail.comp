#version 460
// NAFBlock, last kernel (NAFNet, Chen et al. 2022), all per pixel: conv3 (with the channel attention folded into
// its weights by naf_attention.comp), the beta-scaled residual y = input + beta * conv3(...); then LayerNorm2d,
// the 1x1 conv4 to 2F channels (SimpleGate order), SimpleGate, the 1x1 conv5 back to C, and the gamma-scaled
// residual: output = y + gamma * conv5(...). With PROJECTION_CHANNELS > 0 the block's output goes on through a
// 1x1 conv (the adapter's head) and only that is stored: the block's own output never leaves registers.
// One invocation: PX pixels along x, all channels (each weight read serves PX pixels).
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
layout(constant_id = NN_SPEC_CHANNELS) const int CHANNELS = 4;              // C
layout(constant_id = NN_SPEC_GATED_CHANNELS) const int GATED_CHANNELS = 4;  // conv3's inputs
// F: conv5's inputs, half of conv4's outputs.
layout(constant_id = NN_SPEC_FFN_CHANNELS) const int FFN_CHANNELS = 4;
layout(constant_id = NN_SPEC_EPS) const float EPS = 1e-6;
layout(constant_id = NN_SPEC_PX) const int PX = 1;
layout(constant_id = NN_SPEC_PROJECTION_CHANNELS) const int PROJECTION_CHANNELS = 0;

const int GROUPS = (CHANNELS + 3) / 4;
const int GATED_GROUPS = (GATED_CHANNELS + 3) / 4;
const int FFN_GROUPS = (FFN_CHANNELS + 3) / 4;
const int PROJECTION_GROUPS = (PROJECTION_CHANNELS + 3) / 4;
#define NN_LN_GROUPS GROUPS
#define NN_LN_CHANNELS CHANNELS
#include "nn_layer_norm.glsl"

// Static weights, in this order (vec4 over 4 channels of a group):
const int CONV3_BIAS = 0;                 // [GROUPS]
const int BETA = GROUPS;                  // [GROUPS]
const int NORM2_WEIGHT = 2 * GROUPS;      // [GROUPS]
const int NORM2_BIAS = 3 * GROUPS;        // [GROUPS]
const int CONV4 = 4 * GROUPS;             // per output group of 2 FFN_GROUPS: [input channel], bias
const int CONV4_VEC4S = GROUPS * 4 + 1;
const int CONV5 = CONV4 + 2 * FFN_GROUPS * CONV4_VEC4S;  // per output group of GROUPS: [input channel], bias
const int CONV5_VEC4S = FFN_GROUPS * 4 + 1;
const int GAMMA = CONV5 + GROUPS * CONV5_VEC4S;          // [GROUPS]
const int PROJECTION = GAMMA + GROUPS;  // per output group of PROJECTION_GROUPS: [input channel], bias
const int PROJECTION_VEC4S = GROUPS * 4 + 1;
const int STATIC_VEC4S = PROJECTION + PROJECTION_GROUPS * PROJECTION_VEC4S;

layout(binding = 0) uniform ScaledConv3 { vec4 conv3[GROUPS * GATED_GROUPS * 4]; };  // [output group][input]
layout(binding = 1) uniform Weights { vec4 weights[STATIC_VEC4S]; };
NN_INPUT_MAP(2, gatedMap);  // naf_dw_gate.comp's output
NN_INPUT_MAP(3, inputMap);  // the block's input
NN_OUTPUT_MAP(4, outputMap);

vec4 residual[PX][GROUPS];  // y = input + beta * conv3(gated)
vec4 normed[PX][GROUPS];    // LayerNorm2d(y)
vec4 out5[PX][GROUPS];      // conv5(SimpleGate(conv4(normed)))

// Adds gated group g's part of conv3 to pixel p's `residual`.
void addConv3Group(int p, int g, int x0, int y) {
  const vec4 gated = imageLoad(gatedMap, nnIndex(x0 + p, y, g, WIDTH, HEIGHT));
  [[unroll]] for (int c = 0; c < 4; ++c)
    [[unroll]] for (int o = 0; o < GROUPS; ++o) residual[p][o] += gated[c] * conv3[o * GATED_GROUPS * 4 + g * 4 + c];
}

// FFN group f: its 4 channels of conv4's two halves, SimpleGate, and their part of conv5, added to `out5`.
void addFfnGroup(int f) {
  const int first = CONV4 + f * CONV4_VEC4S, second = CONV4 + (f + FFN_GROUPS) * CONV4_VEC4S;
  vec4 a[PX], b[PX];
  [[unroll]] for (int p = 0; p < PX; ++p) {
    a[p] = weights[first + CONV4_VEC4S - 1];
    b[p] = weights[second + CONV4_VEC4S - 1];
  }
  [[unroll]] for (int i = 0; i < GROUPS * 4; ++i)
    [[unroll]] for (int p = 0; p < PX; ++p) {
      a[p] += normed[p][i / 4][i % 4] * weights[first + i];
      b[p] += normed[p][i / 4][i % 4] * weights[second + i];
    }
  [[unroll]] for (int p = 0; p < PX; ++p) {
    const vec4 gate = a[p] * b[p];  // SimpleGate
    [[unroll]] for (int c = 0; c < 4; ++c)
      [[unroll]] for (int o = 0; o < GROUPS; ++o) out5[p][o] += gate[c] * weights[CONV5 + o * CONV5_VEC4S + f * 4 + c];
  }
}

void main() {
  const int x0 = int(gl_GlobalInvocationID.x) * PX;
  const int y = int(gl_GlobalInvocationID.y);
  if (x0 >= WIDTH || y >= HEIGHT) return;

  [[unroll]] for (int p = 0; p < PX; ++p) {
    [[unroll]] for (int o = 0; o < GROUPS; ++o) residual[p][o] = weights[CONV3_BIAS + o];
    // Small blocks unroll the loops over groups, wide ones loop (nn_tensor.glsl, NN_UNROLLED_GROUPS).
    if (GATED_GROUPS <= NN_UNROLLED_GROUPS) {
      [[unroll]] for (int g = 0; g < GATED_GROUPS; ++g) addConv3Group(p, g, x0, y);
    } else {
      [[dont_unroll]] for (int g = 0; g < GATED_GROUPS; ++g) addConv3Group(p, g, x0, y);
    }
    [[unroll]] for (int o = 0; o < GROUPS; ++o)
      residual[p][o] = imageLoad(inputMap, nnIndex(x0 + p, y, o, WIDTH, HEIGHT)) + weights[BETA + o] * residual[p][o];
  }

  [[unroll]] for (int p = 0; p < PX; ++p) {
    vec4 x[GROUPS];
    [[unroll]] for (int g = 0; g < GROUPS; ++g) x[g] = residual[p][g];
    nnLayerNorm(x, EPS);
    [[unroll]] for (int g = 0; g < GROUPS; ++g) normed[p][g] = x[g] * weights[NORM2_WEIGHT + g] + weights[NORM2_BIAS + g];
  }

  [[unroll]] for (int p = 0; p < PX; ++p)
    [[unroll]] for (int o = 0; o < GROUPS; ++o) out5[p][o] = weights[CONV5 + o * CONV5_VEC4S + CONV5_VEC4S - 1];
  if (FFN_GROUPS <= NN_UNROLLED_GROUPS) {
    [[unroll]] for (int f = 0; f < FFN_GROUPS; ++f) addFfnGroup(f);
  } else {
    [[dont_unroll]] for (int f = 0; f < FFN_GROUPS; ++f) addFfnGroup(f);
  }
  [[unroll]] for (int p = 0; p < PX; ++p) {
    if (x0 + p >= WIDTH) break;
    vec4 block[GROUPS];
    [[unroll]] for (int o = 0; o < GROUPS; ++o) block[o] = residual[p][o] + weights[GAMMA + o] * out5[p][o];
    if (PROJECTION_GROUPS == 0) {
      [[unroll]] for (int o = 0; o < GROUPS; ++o) outputMap[nnIndex(x0 + p, y, o, WIDTH, HEIGHT)] = NN_TEXEL(block[o]);
    } else {
      [[unroll]] for (int o = 0; o < PROJECTION_GROUPS; ++o) {
        const int base = PROJECTION + o * PROJECTION_VEC4S;
        vec4 projected = weights[base + PROJECTION_VEC4S - 1];
        [[unroll]] for (int i = 0; i < GROUPS * 4; ++i) projected += block[i / 4][i % 4] * weights[base + i];
        outputMap[nnIndex(x0 + p, y, o, WIDTH, HEIGHT)] = NN_TEXEL(projected);
      }
    }
  }
}
