// Shadow-map lookups in the obstacle shadow atlas (docs/real-time-rendering.md, "Obstacles and shadows"): one
// D32 depth image, a vertical stack of square tiles of `tileSize` texels, tile t holding the depth map of the
// light with shadow layer t. A light's view-projection takes a world point to Vulkan clip space; in its tile
// u = 0.5 + 0.5·ndc.x, v = 0.5 − 0.5·ndc.y (row 0 at the top), depth 0 at near, 1 at far.
#ifndef SIXWAY_SHADOW_GLSL
#define SIXWAY_SHADOW_GLSL

const float kMaxPcfRadius = 4.0;  // texels; the host refuses larger radii

// Whether the texel (x, y) of tile `tile` (clamped to the tile: clamp-to-edge) lets depth `depth` through.
float shadowTexelLit(sampler2D atlas, int tile, int tileSize, int x, int y, float depth) {
  ivec2 texel = ivec2(clamp(x, 0, tileSize - 1), tile * tileSize + clamp(y, 0, tileSize - 1));
  return depth <= texelFetch(atlas, texel, 0).r ? 1.0 : 0.0;
}

// The lit fraction of `world` for one light: percentage-closer filtering over a box of half-width `radius`
// texels centred on the point, each texel weighted by the area it shares with the box (so a straight occluder
// edge becomes a linear ramp exactly 2·radius texels wide); radius 0: the one texel under the point. The
// point's depth is reduced by `bias` (depth-buffer units) before the comparison. Points outside the light's
// frustum are lit.
float shadowVisibility(sampler2D atlas, int tile, int tileSize, mat4 lightViewProjection, vec3 world,
                       float radius, float bias) {
  vec4 clip = lightViewProjection * vec4(world, 1.0);
  if (clip.w <= 0.0) return 1.0;
  vec3 ndc = clip.xyz / clip.w;
  if (any(greaterThan(abs(ndc.xy), vec2(1.0))) || ndc.z < 0.0 || ndc.z > 1.0) return 1.0;
  vec2 p = vec2(0.5 + 0.5 * ndc.x, 0.5 - 0.5 * ndc.y) * float(tileSize);  // texel units in the tile
  float depth = ndc.z - bias;
  if (radius <= 0.0) return shadowTexelLit(atlas, tile, tileSize, int(floor(p.x)), int(floor(p.y)), depth);

  radius = min(radius, kMaxPcfRadius);
  vec2 lo = p - radius, hi = p + radius;
  ivec2 first = ivec2(floor(lo)), last = ivec2(floor(hi));
  float lit = 0.0;
  for (int y = first.y; y <= last.y; ++y) {
    float wy = min(float(y + 1), hi.y) - max(float(y), lo.y);
    for (int x = first.x; x <= last.x; ++x) {
      float wx = min(float(x + 1), hi.x) - max(float(x), lo.x);
      lit += wx * wy * shadowTexelLit(atlas, tile, tileSize, x, y, depth);
    }
  }
  return lit / (4.0 * radius * radius);
}

// The lit fraction of `world` averaged over a square `halfWidth` metres either side of it across the light's
// beam: a box filter as wide as what the smoke's lightmaps resolve, so a caster's edge on the smoke is not
// sharper than the smoke's own detail. 4 × 4 taps spread evenly over the square, each the texel under it;
// where the square is narrower than `radius` texels, shadowVisibility with that radius. Texels per metre
// from the projection's x row at the point's w (exact for orthographic, the local scale for perspective).
float wideShadowVisibility(sampler2D atlas, int tile, int tileSize, mat4 lightViewProjection, vec3 world,
                           float halfWidth, float radius, float bias) {
  vec4 clip = lightViewProjection * vec4(world, 1.0);
  if (clip.w <= 0.0) return 1.0;
  vec3 ndc = clip.xyz / clip.w;
  if (any(greaterThan(abs(ndc.xy), vec2(1.0))) || ndc.z < 0.0 || ndc.z > 1.0) return 1.0;
  vec3 row = vec3(lightViewProjection[0][0], lightViewProjection[1][0], lightViewProjection[2][0]);
  float spread = halfWidth * 0.5 * float(tileSize) * length(row) / clip.w;  // texels
  if (spread <= radius)
    return shadowVisibility(atlas, tile, tileSize, lightViewProjection, world, radius, bias);
  vec2 p = vec2(0.5 + 0.5 * ndc.x, 0.5 - 0.5 * ndc.y) * float(tileSize);
  float depth = ndc.z - bias, lit = 0.0;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      vec2 t = p + spread * (vec2(i, j) * 0.5 - 0.75);
      lit += shadowTexelLit(atlas, tile, tileSize, int(floor(t.x)), int(floor(t.y)), depth);
    }
  return lit / 16.0;
}

#endif
