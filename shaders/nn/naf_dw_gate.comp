#version 460
// NAFBlock, second kernel (NAFNet, Chen et al. 2022): the 3x3 depthwise conv2 on the 2C expanded channels and
// SimpleGate (group g times group g + GROUPS, see naf_norm_expand.comp), giving C channels. It also sums the
// gated values of each channel for the global average of the simplified channel attention
// (naf_attention.comp): one partial sum per workgroup and channel.
// One invocation: a block of PX x PY pixels, all groups; input rows stream through registers.
#extension GL_GOOGLE_include_directive : require
#ifdef NN_FP16
#extension GL_EXT_shader_16bit_storage : require
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require
#endif
#extension GL_EXT_control_flow_attributes : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
#include "nn_spec.glsl"
#include "nn_tensor.glsl"

layout(local_size_x_id = NN_SPEC_LOCAL_SIZE_X, local_size_y_id = NN_SPEC_LOCAL_SIZE_Y) in;
layout(constant_id = NN_SPEC_WIDTH) const int WIDTH = 1;
layout(constant_id = NN_SPEC_HEIGHT) const int HEIGHT = 1;
layout(constant_id = NN_SPEC_GROUPS) const int GROUPS = 1;  // of the gated output; the input has 2 GROUPS
layout(constant_id = NN_SPEC_PX) const int PX = 4;
layout(constant_id = NN_SPEC_PY) const int PY = 1;

const int SPAN = PX + 2;  // input pixels along x under PX outputs

// Per input group: the 9 taps [ky * 3 + kx] as vec4 over its 4 channels, then bias.
layout(binding = 0) uniform Weights { vec4 weights[2 * GROUPS * 10]; };
NN_INPUT_MAP(1, inputMap);
NN_OUTPUT_MAP(2, outputMap);
layout(std430, binding = 3) writeonly buffer Partials { vec4 partials[]; };  // [workgroup][group]

// Per-subgroup sums (subgroups have at least 4 invocations on every device sixway runs on).
shared vec4 subgroupSums[gl_WorkGroupSize.x * gl_WorkGroupSize.y / 4][GROUPS];

// The depthwise conv of one input group over the invocation's block (bias included).
void depthwise(int group, int x0, int y0, out vec4 acc[PY][PX]) {
  [[unroll]] for (int r = 0; r < PY; ++r)
    [[unroll]] for (int p = 0; p < PX; ++p) acc[r][p] = weights[group * 10 + 9];
  [[unroll]] for (int iy = 0; iy < PY + 2; ++iy) {
    vec4 row[SPAN];
    [[unroll]] for (int i = 0; i < SPAN; ++i) row[i] = imageLoad(inputMap, nnIndex(x0 - 1 + i, y0 - 1 + iy, group, WIDTH, HEIGHT));
    [[unroll]] for (int r = 0; r < PY; ++r) {
      const int ky = iy - r;
      if (ky < 0 || ky > 2) continue;
      [[unroll]] for (int kx = 0; kx < 3; ++kx)
        [[unroll]] for (int p = 0; p < PX; ++p) acc[r][p] += row[p + kx] * weights[group * 10 + ky * 3 + kx];
    }
  }
}

// Gated group g over the invocation's block: stored, and its sum over the subgroup kept for the attention.
void gateGroup(int g, int x0, int y0, bool inside) {
  vec4 sum = vec4(0.0);
  if (inside) {
    vec4 first[PY][PX], second[PY][PX];
    depthwise(g, x0, y0, first);
    depthwise(g + GROUPS, x0, y0, second);
    [[unroll]] for (int r = 0; r < PY; ++r)
      [[unroll]] for (int p = 0; p < PX; ++p)
        if (x0 + p < WIDTH && y0 + r < HEIGHT) {
          const vec4 gated = first[r][p] * second[r][p];
          outputMap[nnIndex(x0 + p, y0 + r, g, WIDTH, HEIGHT)] = NN_TEXEL(gated);
          sum += gated;
        }
  }
  sum = subgroupAdd(sum);
  if (subgroupElect()) subgroupSums[gl_SubgroupID][g] = sum;
}

void main() {
  const int x0 = int(gl_GlobalInvocationID.x) * PX;
  const int y0 = int(gl_GlobalInvocationID.y) * PY;
  const bool inside = x0 < WIDTH && y0 < HEIGHT;  // no early return: every invocation reaches the barrier
  // Small blocks unroll the loop over groups, wide ones loop (nn_tensor.glsl, NN_UNROLLED_GROUPS).
  if (GROUPS <= NN_UNROLLED_GROUPS) {
    [[unroll]] for (int g = 0; g < GROUPS; ++g) gateGroup(g, x0, y0, inside);
  } else {
    [[dont_unroll]] for (int g = 0; g < GROUPS; ++g) gateGroup(g, x0, y0, inside);
  }
  barrier();
  const uint local = gl_LocalInvocationIndex;
  if (local < uint(GROUPS)) {
    vec4 total = vec4(0.0);
    for (uint s = 0; s < gl_NumSubgroups; ++s) total += subgroupSums[s][local];
    partials[(gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * GROUPS + local] = total;
  }
}
