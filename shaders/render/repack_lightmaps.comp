#version 460
// The lightmaps in an engine's packing (render/lightmap_packing.h, docs/formats.md "Packing presets"): each
// component of the two output textures takes one component of Unity's A and B (the network's and the
// shading's packing), or 0.

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba16f) uniform readonly image2D lightmapA;
layout(binding = 1, rgba16f) uniform readonly image2D lightmapB;
layout(binding = 2, rgba16f) uniform writeonly image2D first;
layout(binding = 3, rgba16f) uniform writeonly image2D second;
// Per output component: the source component, 0..3 of A, 4..7 of B; −1: zero.
layout(push_constant) uniform Push {
  ivec4 firstSources;
  ivec4 secondSources;
} push;

vec4 gather(ivec4 sources, vec4 a, vec4 b) {
  vec4 result;
  for (int c = 0; c < 4; ++c)
    result[c] = sources[c] < 0 ? 0.0 : (sources[c] < 4 ? a[sources[c]] : b[sources[c] - 4]);
  return result;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, imageSize(lightmapA)))) return;
  vec4 a = imageLoad(lightmapA, pixel), b = imageLoad(lightmapB, pixel);
  imageStore(first, pixel, gather(push.firstSources, a, b));
  imageStore(second, pixel, gather(push.secondSources, a, b));
}
