#version 460
// The network's input: the guiding map (any float format, read through a sampler) copied into the first
// feature map, its first GUIDE_CHANNELS channels kept and the rest zero; a 5th guide channel, the direct
// emission, comes from the R channel of a second image into the map's second group of four. The map may be
// larger than the guide (rounded up to the network's size multiple); the extra pixels are zero. A network that
// reads the smoke's albedo (a scene constant) has it, encoded by the host, in channel ALBEDO_CHANNEL of every
// pixel, the extra ones too.
#extension GL_GOOGLE_include_directive : require
#ifdef NN_FP16
#extension GL_EXT_shader_16bit_storage : require
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require
#endif
#include "nn_spec.glsl"
#include "nn_tensor.glsl"

layout(local_size_x_id = NN_SPEC_LOCAL_SIZE_X, local_size_y_id = NN_SPEC_LOCAL_SIZE_Y) in;
layout(constant_id = NN_SPEC_WIDTH) const int WIDTH = 1;  // of the feature map
layout(constant_id = NN_SPEC_HEIGHT) const int HEIGHT = 1;
layout(constant_id = NN_SPEC_CHANNELS) const int CHANNELS = 4;  // of the feature map: 4 or 8
layout(constant_id = NN_SPEC_GUIDE_WIDTH) const int GUIDE_WIDTH = 1;
layout(constant_id = NN_SPEC_GUIDE_HEIGHT) const int GUIDE_HEIGHT = 1;
layout(constant_id = NN_SPEC_GUIDE_CHANNELS) const int GUIDE_CHANNELS = 3;
layout(constant_id = NN_SPEC_ALBEDO_CHANNEL) const int ALBEDO_CHANNEL = -1;  // -1: none

layout(binding = 0) uniform sampler2D guide;
NN_OUTPUT_MAP(1, outputMap);
layout(binding = 2) uniform sampler2D emission;  // read when GUIDE_CHANNELS is 5
layout(std430, binding = 3) readonly buffer Scene {
  float albedo;  // (albedo - offset) * scale, the input node's encoding
};

// `value` (channels 4 group .. 4 group + 3) with the albedo in its channel, if that is in this group.
vec4 withAlbedo(vec4 value, int group) {
  const int k = ALBEDO_CHANNEL - 4 * group;
  return k >= 0 && k < 4 ? mix(value, vec4(albedo), equal(ivec4(0, 1, 2, 3), ivec4(k))) : value;
}

void main() {
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= WIDTH || pixel.y >= HEIGHT) return;
  const bool inside = pixel.x < GUIDE_WIDTH && pixel.y < GUIDE_HEIGHT;
  vec4 value = vec4(0.0);
  if (inside) value = texelFetch(guide, pixel, 0) * vec4(lessThan(ivec4(0, 1, 2, 3), ivec4(GUIDE_CHANNELS)));
  outputMap[nnIndex(pixel.x, pixel.y, 0, WIDTH, HEIGHT)] = NN_TEXEL(withAlbedo(value, 0));
  if (CHANNELS > 4) {
    float emitted = inside && GUIDE_CHANNELS > 4 ? texelFetch(emission, pixel, 0).r : 0.0;
    outputMap[nnIndex(pixel.x, pixel.y, 1, WIDTH, HEIGHT)] = NN_TEXEL(withAlbedo(vec4(emitted, 0.0, 0.0, 0.0), 1));
  }
}
