#version 460
// Guide-lit lightmaps, the "guide only" baseline of the evaluation (docs/real-time-rendering.md, "Guide-lit
// lightmaps"): without the network, the best the guiding map says about each light direction is the mean
// light of its guide lights. The guide's R is the sum of the in-scattered light under its kGuideLights
// surrogate lights (the baker's normalisation, premultiplied), so every one of the six light channels gets
// R / kGuideLights; alpha is the guide's G (1 − T); there is no emission.
// Lightmaps in Unity's packing: A = (Right, Top, Back, alpha), B = (Left, Bottom, Front, emissive).

layout(local_size_x = 8, local_size_y = 8) in;

layout(constant_id = 0) const int kGuideLights = 3;

layout(binding = 0, rgba16f) uniform readonly image2D guide;
layout(binding = 1, rgba16f) uniform writeonly image2D lightmapA;
layout(binding = 2, rgba16f) uniform writeonly image2D lightmapB;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, imageSize(guide)))) return;
  vec4 g = imageLoad(guide, pixel);
  float light = g.r / float(kGuideLights);
  imageStore(lightmapA, pixel, vec4(light, light, light, g.g));
  imageStore(lightmapB, pixel, vec4(light, light, light, 0.0));
}
