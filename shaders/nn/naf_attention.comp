#version 460
// NAFBlock, third kernel (NAFNet, Chen et al. 2022): the simplified channel attention. One workgroup sums the
// per-workgroup partial sums of naf_dw_gate.comp into the global average of each gated channel, applies the
// attention's 1x1 conv (sca) to get one scale per channel, and folds the scales into conv3: it writes
// conv3.weight[o][i] * scale[i], which naf_tail.comp reads as its first 1x1 conv. (x * s then conv3 equals
// conv3 with scaled weights; the per-pixel work stays one matrix product.)
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require
#include "nn_spec.glsl"

layout(local_size_x_id = NN_SPEC_LOCAL_SIZE_X) in;
layout(constant_id = NN_SPEC_GATED_CHANNELS) const int GATED_CHANNELS = 4;
layout(constant_id = NN_SPEC_CHANNELS) const int CHANNELS = 4;            // block channels: conv3's outputs
layout(constant_id = NN_SPEC_PARTIAL_COUNT) const int PARTIAL_COUNT = 1;  // workgroups of naf_dw_gate.comp
layout(constant_id = NN_SPEC_PIXELS) const float PIXELS = 1.0;

const int GATED_GROUPS = (GATED_CHANNELS + 3) / 4;
const int OUT_GROUPS = (CHANNELS + 3) / 4;
// sca: per output group, [input channel] vec4 weights then bias; then conv3, per output group, [input channel].
const int SCA_VEC4S = GATED_GROUPS * (GATED_GROUPS * 4 + 1);
const int CONV3_VEC4S = OUT_GROUPS * GATED_GROUPS * 4;

layout(std430, binding = 0) readonly buffer Partials { vec4 partials[]; };  // [workgroup][gated group]
layout(binding = 1) uniform Weights { vec4 weights[SCA_VEC4S + CONV3_VEC4S]; };
layout(std430, binding = 2) writeonly buffer ScaledConv3 { vec4 scaledConv3[]; };

shared vec4 reduction[gl_WorkGroupSize.x];
shared vec4 means[GATED_GROUPS];
shared vec4 scales[GATED_GROUPS];

void main() {
  const uint local = gl_LocalInvocationID.x;
  for (int g = 0; g < GATED_GROUPS; ++g) {
    vec4 sum = vec4(0.0);
    for (uint i = local; i < uint(PARTIAL_COUNT); i += gl_WorkGroupSize.x) sum += partials[i * GATED_GROUPS + g];
    reduction[local] = sum;
    barrier();
    for (uint stride = gl_WorkGroupSize.x / 2; stride > 0; stride /= 2) {
      if (local < stride) reduction[local] += reduction[local + stride];
      barrier();
    }
    if (local == 0) means[g] = reduction[0] / PIXELS;
    barrier();
  }
  if (local < uint(GATED_GROUPS)) {
    const int base = int(local) * (GATED_GROUPS * 4 + 1);
    vec4 scale = weights[base + GATED_GROUPS * 4];
    for (int i = 0; i < GATED_GROUPS * 4; ++i) scale += means[i / 4][i % 4] * weights[base + i];
    scales[local] = scale;
  }
  barrier();
  for (uint i = local; i < uint(CONV3_VEC4S); i += gl_WorkGroupSize.x) {
    const int column = int(i) % (GATED_GROUPS * 4);  // the gated input channel
    scaledConv3[i] = weights[SCA_VEC4S + i] * scales[column / 4][column % 4];
  }
}
