#version 460
// The network's output: eight channels taken from up to four head feature maps (channel k is component
// SOURCE_k % 4 of map SOURCE_k / 4, or the constant 0 where SOURCE_k < 0: smoke without emission),
// decoded from the network's encoding (sRGB where bit k of SRGB_MASK is set),
// clamped at 0 (radiance and alpha are never negative), and packed into the two lightmaps
// (docs/conventions.md, "Channels and packing": A = Right, Top, Back, alpha; B = Left, Bottom, Front,
// emissive), cropped to the lightmaps' size.
#extension GL_GOOGLE_include_directive : require
#ifdef NN_FP16
#extension GL_EXT_shader_16bit_storage : require
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require
#endif
#extension GL_EXT_control_flow_attributes : require
#include "nn_spec.glsl"
#include "nn_tensor.glsl"

layout(local_size_x_id = NN_SPEC_LOCAL_SIZE_X, local_size_y_id = NN_SPEC_LOCAL_SIZE_Y) in;
layout(constant_id = NN_SPEC_WIDTH) const int WIDTH = 1;            // of the lightmaps
layout(constant_id = NN_SPEC_HEIGHT) const int HEIGHT = 1;
layout(constant_id = NN_SPEC_MAP_HEIGHT) const int MAP_HEIGHT = 1;  // of the head feature maps
layout(constant_id = NN_SPEC_SRGB_MASK) const int SRGB_MASK = 0;
layout(constant_id = NN_SPEC_SOURCE_0) const int SOURCE_0 = 0;
layout(constant_id = NN_SPEC_SOURCE_1) const int SOURCE_1 = 1;
layout(constant_id = NN_SPEC_SOURCE_2) const int SOURCE_2 = 4;
layout(constant_id = NN_SPEC_SOURCE_3) const int SOURCE_3 = 5;
layout(constant_id = NN_SPEC_SOURCE_4) const int SOURCE_4 = 8;
layout(constant_id = NN_SPEC_SOURCE_5) const int SOURCE_5 = 9;
layout(constant_id = NN_SPEC_SOURCE_6) const int SOURCE_6 = 12;
layout(constant_id = NN_SPEC_SOURCE_7) const int SOURCE_7 = 13;
// Which of the eight channels go to the components of lightmap A and B.
layout(constant_id = NN_SPEC_A_0) const int A_0 = 0;
layout(constant_id = NN_SPEC_A_1) const int A_1 = 1;
layout(constant_id = NN_SPEC_A_2) const int A_2 = 2;
layout(constant_id = NN_SPEC_A_3) const int A_3 = 3;
layout(constant_id = NN_SPEC_B_0) const int B_0 = 4;
layout(constant_id = NN_SPEC_B_1) const int B_1 = 5;
layout(constant_id = NN_SPEC_B_2) const int B_2 = 6;
layout(constant_id = NN_SPEC_B_3) const int B_3 = 7;
layout(constant_id = NN_SPEC_MAP_WIDTH) const int MAP_WIDTH = 1;

NN_INPUT_MAP(0, head0);
NN_INPUT_MAP(1, head1);
NN_INPUT_MAP(2, head2);
NN_INPUT_MAP(3, head3);
layout(binding = 4) uniform writeonly image2D lightmapA;  // any float format: written without one
layout(binding = 5) uniform writeonly image2D lightmapB;

float srgbToLinear(float v) {
  return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

void main() {
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= WIDTH || pixel.y >= HEIGHT) return;
  const int texel = nnIndex(pixel.x, pixel.y, 0, MAP_WIDTH, MAP_HEIGHT);
  const vec4 texels[4] = vec4[4](imageLoad(head0, texel), imageLoad(head1, texel), imageLoad(head2, texel),
                                 imageLoad(head3, texel));
  const int sources[8] = int[8](SOURCE_0, SOURCE_1, SOURCE_2, SOURCE_3, SOURCE_4, SOURCE_5, SOURCE_6, SOURCE_7);
  float channels[8];
  [[unroll]] for (int k = 0; k < 8; ++k) {
    if (sources[k] < 0) {
      channels[k] = 0.0;
      continue;
    }
    float v = texels[sources[k] / 4][sources[k] % 4];
    if ((SRGB_MASK & (1 << k)) != 0) v = srgbToLinear(v);
    channels[k] = max(v, 0.0);
  }
  imageStore(lightmapA, pixel, vec4(channels[A_0], channels[A_1], channels[A_2], channels[A_3]));
  imageStore(lightmapB, pixel, vec4(channels[B_0], channels[B_1], channels[B_2], channels[B_3]));
}
