// A texture magnified through the Catmull-Rom cubic (Catmull & Rom 1974; the a = −1/2 cubic convolution of
// Keys 1981): interpolating (texel centres keep their values, so no blur), C1 across texel edges, where the
// bilinear lookup is only C0 and draws a smoke edge stretched over many pixels as axis-aligned steps. 16
// texelFetch taps, edges clamped, as CPU oracles can repeat exactly. The negative lobes over- and undershoot
// a step by up to 0.074 of its height (w at t = 2/3): callers clamp what must stay in range.
#ifndef SIXWAY_CATMULL_ROM_GLSL
#define SIXWAY_CATMULL_ROM_GLSL

// The four weights of the taps at −1, 0, 1, 2 texels from the one below the point, which lies t past it.
vec4 catmullRomWeights(float t) {
  float t2 = t * t, t3 = t2 * t;
  return vec4(-0.5 * t3 + t2 - 0.5 * t, 1.5 * t3 - 2.5 * t2 + 1.0, -1.5 * t3 + 2.0 * t2 + 0.5 * t,
              0.5 * t3 - 0.5 * t2);
}

// `map` at uv (0..1 across it; texel centres at (i + 0.5) / size).
vec4 textureCatmullRom(sampler2D map, vec2 uv) {
  ivec2 size = textureSize(map, 0);
  vec2 g = uv * vec2(size) - 0.5;
  ivec2 base = ivec2(floor(g));
  vec2 f = g - vec2(base);
  vec4 wx = catmullRomWeights(f.x), wy = catmullRomWeights(f.y);
  vec4 sum = vec4(0.0);
  for (int j = 0; j < 4; ++j) {
    vec4 row = vec4(0.0);
    int y = clamp(base.y + j - 1, 0, size.y - 1);
    for (int i = 0; i < 4; ++i)
      row += wx[i] * texelFetch(map, ivec2(clamp(base.x + i - 1, 0, size.x - 1), y), 0);
    sum += wy[j] * row;
  }
  return sum;
}

#endif
