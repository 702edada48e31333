#version 460
// Conv2d of PyTorch (kernel 1 or 3, zero padding kernel/2, stride 1 or 2) over the channel concatenation of
// one or two feature maps (concatenation by addressing: input A's groups come first, then input B's), then
// bias and activation. One invocation computes a block of PX x PY output pixels for one output channel group
// (4 channels), the workgroup's z index: each input texel loaded serves up to 9 PX PY / ((PX + 2) (PY + 2))
// outputs, and the block's accumulators still fit in registers on lavapipe (measured fastest at 4 x 8).
// Input groups are taken SLICE at a time: a slice is unrolled, the slices are a loop, so the shader's size (and
// lavapipe's compile time) stays bounded however many channels a layer has.
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
layout(constant_id = NN_SPEC_KERNEL) const int KERNEL = 3;
layout(constant_id = NN_SPEC_STRIDE) const int STRIDE = 1;
layout(constant_id = NN_SPEC_IN_HEIGHT) const int IN_HEIGHT = 1;
layout(constant_id = NN_SPEC_OUT_WIDTH) const int OUT_WIDTH = 1;
layout(constant_id = NN_SPEC_OUT_HEIGHT) const int OUT_HEIGHT = 1;
// Channel groups read from input A and from input B (0: one input).
layout(constant_id = NN_SPEC_GROUPS_A) const int GROUPS_A = 1;
layout(constant_id = NN_SPEC_GROUPS_B) const int GROUPS_B = 0;
layout(constant_id = NN_SPEC_PX) const int PX = 4;
layout(constant_id = NN_SPEC_PY) const int PY = 1;
layout(constant_id = NN_SPEC_SLICE) const int SLICE = 4;
layout(constant_id = NN_SPEC_ACTIVATION) const int ACTIVATION = NN_ACT_NONE;
layout(constant_id = NN_SPEC_NEGATIVE_SLOPE) const float NEGATIVE_SLOPE = 0.0;
// The size of this dispatch's weight chunk.
layout(constant_id = NN_SPEC_WEIGHT_VEC4S) const int WEIGHT_VEC4S = 1;
layout(constant_id = NN_SPEC_IN_WIDTH) const int IN_WIDTH = 1;

// Per output group: weights [input channel][ky][kx] as vec4 over the group's 4 output channels, then bias.
const int GROUP_VEC4S = (GROUPS_A + GROUPS_B) * 4 * KERNEL * KERNEL + 1;
const int SPAN = (PX - 1) * STRIDE + KERNEL;  // input pixels along x under PX outputs
const int ROWS = (PY - 1) * STRIDE + KERNEL;  // input rows under PY outputs

NN_INPUT_MAP(0, inputA);
NN_INPUT_MAP(1, inputB);
layout(binding = 2) uniform Weights { vec4 weights[WEIGHT_VEC4S]; };
NN_OUTPUT_MAP(3, outputMap);
layout(push_constant) uniform Push {
  int firstGroup;  // the output group of the chunk's first (workgroup z = 0)
} push;

vec4 acc[PY][PX];  // the invocation's output block

// Adds input group `group` (of input B when `fromB`, a constant at every call) to the block's sums; `weightGroup`
// is its place among the concatenated groups.
void accumulate(bool fromB, int group, int weightGroup, int base, int x0, int y0) {
  [[unroll]] for (int iy = 0; iy < ROWS; ++iy) {
    vec4 row[SPAN];
    [[unroll]] for (int i = 0; i < SPAN; ++i) {
      const int texel = nnIndex(x0 * STRIDE - KERNEL / 2 + i, y0 * STRIDE - KERNEL / 2 + iy, group, IN_WIDTH, IN_HEIGHT);
      row[i] = fromB ? imageLoad(inputB, texel) : imageLoad(inputA, texel);
    }
    [[unroll]] for (int r = 0; r < PY; ++r) {
      const int ky = iy - r * STRIDE;  // the kernel row that input row iy is for output row r
      if (ky < 0 || ky >= KERNEL) continue;
      [[unroll]] for (int c = 0; c < 4; ++c)
        [[unroll]] for (int kx = 0; kx < KERNEL; ++kx) {
          const vec4 w = weights[base + ((weightGroup * 4 + c) * KERNEL + ky) * KERNEL + kx];
          [[unroll]] for (int p = 0; p < PX; ++p) acc[r][p] += row[p * STRIDE + kx][c] * w;
        }
    }
  }
}

// All groups of one input: unrolled when the layer has at most 2 SLICE input groups in all, else whole slices in
// a loop, then the remainder unrolled. (Measured on lavapipe: a loop over 2-group slices runs 45-65 GFLOP/s and
// compiles in about 2 s however many channels; unrolling up to 4 groups is faster still; more is slower.)
void accumulateInput(bool fromB, int groups, int x0, int y0, int base) {
  const int offset = fromB ? GROUPS_A : 0;
  if (GROUPS_A + GROUPS_B <= 2 * SLICE) {
    [[unroll]] for (int g = 0; g < groups; ++g) accumulate(fromB, g, offset + g, base, x0, y0);
    return;
  }
  [[dont_unroll]] for (int s = 0; s + SLICE <= groups; s += SLICE)
    [[unroll]] for (int k = 0; k < SLICE; ++k) accumulate(fromB, s + k, offset + s + k, base, x0, y0);
  [[unroll]] for (int g = groups / SLICE * SLICE; g < groups; ++g) accumulate(fromB, g, offset + g, base, x0, y0);
}

void main() {
  const int x0 = int(gl_GlobalInvocationID.x) * PX;
  const int y0 = int(gl_GlobalInvocationID.y) * PY;
  if (x0 >= OUT_WIDTH || y0 >= OUT_HEIGHT) return;
  const int base = int(gl_WorkGroupID.z) * GROUP_VEC4S;

  [[unroll]] for (int r = 0; r < PY; ++r)
    [[unroll]] for (int p = 0; p < PX; ++p) acc[r][p] = weights[base + GROUP_VEC4S - 1];
  accumulateInput(false, GROUPS_A, x0, y0, base);
  if (GROUPS_B > 0) accumulateInput(true, GROUPS_B, x0, y0, base);
  const int outGroup = push.firstGroup + int(gl_WorkGroupID.z);
  [[unroll]] for (int r = 0; r < PY; ++r)
    [[unroll]] for (int p = 0; p < PX; ++p)
      if (x0 + p < OUT_WIDTH && y0 + r < OUT_HEIGHT)
        outputMap[nnIndex(x0 + p, y0 + r, outGroup, OUT_WIDTH, OUT_HEIGHT)] =
            NN_TEXEL(nnActivate(acc[r][p], ACTIVATION, NEGATIVE_SLOPE));
}
