// Feature maps of the network (src/nn/feature_map.h): C channels of an H x W map in one buffer of RGBA texels,
// ceil(C/4) channel groups of H + 2 rows each, rows of nnRowTexels(W) texels. Each group is framed by a
// one-texel zero border, so a 3x3 (or stride-2) read one pixel outside the map returns zero without a bounds
// check: group g, pixel (x, y) is texel (g (H + 2) + y + 1) nnRowTexels(W) + x + 1. Channels past C within the
// last group are 0. The buffer has slack texels to the right and below, so a pixel block that overhangs the map
// reads inside it; outputs outside the map are not stored.
// Kernels write a map as a storage buffer and read it through a texel view (imageLoad): on lavapipe these are
// the cheapest writes and reads. NN_FP16 variants store RGBA16F texels (arithmetic stays fp32; the shader
// enables GL_EXT_shader_16bit_storage); the default is RGBA32F.
#ifndef SIXWAY_NN_TENSOR_GLSL
#define SIXWAY_NN_TENSOR_GLSL

// Channel groups up to which a kernel unrolls its loops over groups; wider layers loop over them instead. On
// lavapipe the compile time grows faster than the unrolled code: NAFBlocks of 64 channels, fully unrolled, took
// over 14 minutes to build (measured in the model study), while the adapters' 16 channels run fastest unrolled.
#define NN_UNROLLED_GROUPS 4

#ifdef NN_FP16
#define NN_FORMAT rgba16f
#define NN_TEXEL f16vec4
#else
#define NN_FORMAT rgba32f
#define NN_TEXEL vec4
#endif

// A map read by the kernel, and a map it writes (`name[index] = NN_TEXEL(value)`).
#define NN_INPUT_MAP(index, name) layout(binding = index, NN_FORMAT) uniform readonly imageBuffer name
#define NN_OUTPUT_MAP(index, name) \
  layout(std430, binding = index) writeonly buffer name##Texels { NN_TEXEL name[]; }

int nnRowTexels(int width) {
  return (width + 7) / 8 * 8 + 2;
}

int nnIndex(int x, int y, int group, int width, int height) {
  return (group * (height + 2) + y + 1) * nnRowTexels(width) + x + 1;
}

#endif
