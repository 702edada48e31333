#version 460
// Conv2d as conv2d.comp computes it (kernel 1 or 3, zero padding kernel/2, stride 1 or 2, one or two
// concatenated inputs, bias, activation), on cooperative matrices (GL_NV_cooperative_matrix: an NVIDIA GPU's
// tensor cores), as an implicit matrix product
//   out[pixel][o] = bias[o] + sum_k A[pixel][k] W[k][o],   k = (tap * GROUPS + g) * 4 + c,
// over the kernel's taps (tap = ky * KERNEL + kx), the input channel groups (input A's, then B's) and their
// 4 channels. A workgroup is SUBGROUPS subgroups, each owning MATRIX_M consecutive output pixels (in row-major
// order over the map) and the workgroup's N_TILES * MATRIX_N output channels (workgroup y picks which). The
// texels under the workgroup's pixels are gathered into shared memory STAGE_K values of k at a time, rounded
// to fp16; each subgroup multiplies its rows by the weights' fp16 MATRIX_K x MATRIX_N tiles, read from a
// storage buffer, and accumulates in fp32. Bias and activation are applied on the way out, as in conv2d.comp.
// Only the NN_FP16 variant is built: the maps are fp16 already, so the products see no further rounding of the
// inputs, only of the weights (2^-11 relative).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_16bit_storage : require
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_memory_scope_semantics : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_NV_cooperative_matrix : require
#include "nn_spec.glsl"
#include "nn_activation.glsl"
#include "nn_tensor.glsl"

// Subgroups of 32 invocations (the host uses this kernel only where the subgroup size is 32).
const int SUBGROUPS = 4;
layout(local_size_x = 128) in;
layout(constant_id = NN_SPEC_KERNEL) const int KERNEL = 3;
layout(constant_id = NN_SPEC_STRIDE) const int STRIDE = 1;
layout(constant_id = NN_SPEC_IN_WIDTH) const int IN_WIDTH = 1;
layout(constant_id = NN_SPEC_IN_HEIGHT) const int IN_HEIGHT = 1;
layout(constant_id = NN_SPEC_OUT_WIDTH) const int OUT_WIDTH = 1;
layout(constant_id = NN_SPEC_OUT_HEIGHT) const int OUT_HEIGHT = 1;
// Channel groups read from input A and from input B (0: one input).
layout(constant_id = NN_SPEC_GROUPS_A) const int GROUPS_A = 1;
layout(constant_id = NN_SPEC_GROUPS_B) const int GROUPS_B = 0;
layout(constant_id = NN_SPEC_ACTIVATION) const int ACTIVATION = NN_ACT_NONE;
layout(constant_id = NN_SPEC_NEGATIVE_SLOPE) const float NEGATIVE_SLOPE = 0.0;
// The matrix shape the device offers (VkCooperativeMatrixPropertiesNV: fp16 A and B, fp32 C and D).
layout(constant_id = NN_SPEC_MATRIX_M) const int MATRIX_M = 16;
layout(constant_id = NN_SPEC_MATRIX_N) const int MATRIX_N = 8;
layout(constant_id = NN_SPEC_MATRIX_K) const int MATRIX_K = 16;
// Output channel tiles per workgroup; K chunks of the weights; the weights' row length (padded output channels);
// the output channel groups stored (the layer's).
layout(constant_id = NN_SPEC_N_TILES) const int N_TILES = 1;
layout(constant_id = NN_SPEC_K_CHUNKS) const int K_CHUNKS = 1;
layout(constant_id = NN_SPEC_N_PADDED) const int N_PADDED = 8;
layout(constant_id = NN_SPEC_OUT_GROUPS) const int OUT_GROUPS = 1;

const int GROUPS = GROUPS_A + GROUPS_B;
const int TEXELS = KERNEL * KERNEL * GROUPS;  // input texels under one output pixel: K / 4
const int PIXELS = OUT_WIDTH * OUT_HEIGHT;
const int TILE_PIXELS = SUBGROUPS * MATRIX_M;  // output pixels per workgroup
const int TILE_CHANNELS = N_TILES * MATRIX_N;  // output channels per workgroup
const int STAGE_CHUNKS = 4;                    // K chunks gathered between two barriers
const int STAGE_K = STAGE_CHUNKS * MATRIX_K;
const int STAGE_TEXELS = STAGE_K / 4;
// Halves per row of the gathered block: 8 more than a stage (16 bytes) so that the rows a matrix load reads
// start in different shared-memory banks. Every offset and stride of a matrix load or store below is a multiple
// of 16 bytes, as the cooperative-matrix loads require.
const int A_STRIDE = STAGE_K + 8;

NN_INPUT_MAP(0, inputA);
NN_INPUT_MAP(1, inputB);
// W[k][o] as fp16, K_CHUNKS * MATRIX_K rows of N_PADDED (zero past the layer's k and o).
layout(std430, binding = 2) readonly buffer Weights { float16_t weights[]; };
layout(std430, binding = 3) readonly buffer Bias { float bias[]; };  // N_PADDED values
NN_OUTPUT_MAP(4, outputMap);

shared float16_t gathered[TILE_PIXELS * A_STRIDE];  // A: the workgroup's pixels x one stage of k
shared float sums[TILE_PIXELS * TILE_CHANNELS];      // the products, for the way out

// Gathers stage `stage` of A for the workgroup's pixels: consecutive invocations take consecutive pixels of
// one texel column, so their loads are consecutive texels of a row. Pixels past the map and k past the layer
// are zero.
void gather(int stage, int firstPixel) {
  for (int slot = int(gl_LocalInvocationIndex); slot < TILE_PIXELS * STAGE_TEXELS; slot += SUBGROUPS * 32) {
    const int p = slot % TILE_PIXELS, column = slot / TILE_PIXELS;
    const int texel = stage * STAGE_TEXELS + column, pixel = firstPixel + p;
    vec4 v = vec4(0.0);
    if (texel < TEXELS && pixel < PIXELS) {
      const int tap = texel / GROUPS, g = texel % GROUPS;
      const int x = (pixel % OUT_WIDTH) * STRIDE - KERNEL / 2 + tap % KERNEL;
      const int y = (pixel / OUT_WIDTH) * STRIDE - KERNEL / 2 + tap / KERNEL;
      v = g < GROUPS_A ? imageLoad(inputA, nnIndex(x, y, g, IN_WIDTH, IN_HEIGHT))
                       : imageLoad(inputB, nnIndex(x, y, g - GROUPS_A, IN_WIDTH, IN_HEIGHT));
    }
    const int at = p * A_STRIDE + column * 4;
    [[unroll]] for (int c = 0; c < 4; ++c) gathered[at + c] = float16_t(v[c]);
  }
}

void main() {
  const int firstPixel = int(gl_WorkGroupID.x) * TILE_PIXELS;
  const int firstChannel = int(gl_WorkGroupID.y) * TILE_CHANNELS;
  const uint rows = gl_SubgroupID * uint(MATRIX_M);  // this subgroup's pixels within the workgroup's

  fcoopmatNV<32, gl_ScopeSubgroup, MATRIX_M, MATRIX_N> acc[N_TILES];
  [[unroll]] for (int n = 0; n < N_TILES; ++n) acc[n] = fcoopmatNV<32, gl_ScopeSubgroup, MATRIX_M, MATRIX_N>(0.0);
  const int stages = (K_CHUNKS + STAGE_CHUNKS - 1) / STAGE_CHUNKS;
  for (int stage = 0; stage < stages; ++stage) {
    gather(stage, firstPixel);
    barrier();
    [[unroll]] for (int c = 0; c < STAGE_CHUNKS; ++c) {
      const int chunk = stage * STAGE_CHUNKS + c;
      if (chunk >= K_CHUNKS) break;
      fcoopmatNV<16, gl_ScopeSubgroup, MATRIX_M, MATRIX_K> a;
      coopMatLoadNV(a, gathered, rows * A_STRIDE + uint(c * MATRIX_K), uint(A_STRIDE), false);
      [[unroll]] for (int n = 0; n < N_TILES; ++n) {
        fcoopmatNV<16, gl_ScopeSubgroup, MATRIX_K, MATRIX_N> b;
        coopMatLoadNV(b, weights, uint(chunk * MATRIX_K * N_PADDED + firstChannel + n * MATRIX_N), uint(N_PADDED),
                      false);
        acc[n] = coopMatMulAddNV(a, b, acc[n]);
      }
    }
    barrier();
  }
  [[unroll]] for (int n = 0; n < N_TILES; ++n)
    coopMatStoreNV(acc[n], sums, rows * TILE_CHANNELS + uint(n * MATRIX_N), uint(TILE_CHANNELS), false);
  barrier();

  for (int slot = int(gl_LocalInvocationIndex); slot < TILE_PIXELS * TILE_CHANNELS / 4; slot += SUBGROUPS * 32) {
    const int p = slot % TILE_PIXELS, column = slot / TILE_PIXELS;
    const int pixel = firstPixel + p, group = firstChannel / 4 + column;
    if (pixel >= PIXELS || group >= OUT_GROUPS) continue;
    const int at = p * TILE_CHANNELS + column * 4;
    const vec4 sum = vec4(sums[at], sums[at + 1], sums[at + 2], sums[at + 3]) +
                     vec4(bias[group * 4], bias[group * 4 + 1], bias[group * 4 + 2], bias[group * 4 + 3]);
    outputMap[nnIndex(pixel % OUT_WIDTH, pixel / OUT_WIDTH, group, OUT_WIDTH, OUT_HEIGHT)] =
        NN_TEXEL(nnActivate(sum, ACTIVATION, NEGATIVE_SLOPE));
  }
}
