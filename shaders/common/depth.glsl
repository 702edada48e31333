// View depths (distance along the camera's forward axis) as the real-time renderer stores them
// (docs/real-time-rendering.md): the shell depth in the guiding map's third channel, linear in the volume's
// depth range, and the depth buffer of a perspective projection (src/render/projection.h).
#ifndef SIXWAY_DEPTH_GLSL
#define SIXWAY_DEPTH_GLSL

#include "camera.glsl"

// range = (near, far): the view depths of the volume box (render::boxDepthRange). The guide stores
// (z − near) / (far − near); 1 where the view ray's opacity never reaches the shell threshold.
float encodeShellDepth(float viewDepth, vec2 range) {
  return clamp((viewDepth - range.x) / (range.y - range.x), 0.0, 1.0);
}
float decodeShellDepth(float encoded, vec2 range) {
  return mix(range.x, range.y, encoded);
}

// The view depth of the shaded point at `uv` (0..1 across the guide): bilinear over the four nearest guide
// texels, each the shell's depth where it has one and `planeDepth` (the billboard's) where it has none. The
// shaded point, and with it an obstacle's shadow edge, then moves smoothly across the smoke instead of in
// steps of a guide texel, which a 64² guide under a 512² frame shows as 8-pixel blocks.
float interpolatedShadedDepth(sampler2D guide, vec2 uv, vec2 range, float planeDepth) {
  ivec2 size = textureSize(guide, 0);
  vec2 g = uv * vec2(size) - 0.5;
  ivec2 base = ivec2(floor(g));
  vec2 t = g - vec2(base);
  float depth = 0.0;
  for (int k = 0; k < 4; ++k) {
    ivec2 corner = ivec2(k & 1, k >> 1);
    float shell = texelFetch(guide, clamp(base + corner, ivec2(0), size - 1), 0).b;
    vec2 w = mix(1.0 - t, t, vec2(corner));
    depth += w.x * w.y * (shell < 1.0 ? decodeShellDepth(shell, range) : planeDepth);
  }
  return depth;
}

// How the smoke's opacity builds up along a view ray (the guide's opacity depths, guide_march.comp): the view
// depths where 1 − T first reaches each of these levels.
const float kOpacityLevels[4] = float[4](0.1, 0.35, 0.6, 0.85);

// The opacity of the smoke in front of view depth d along a ray whose opacity reaches `total` and the levels
// at `depths` (< 0: not reached) is piecewise linear through these knots (depth, opacity), at most 6: from 0
// a quarter of the first two levels' distance before the first (0.1 of the 0.25 between them), through the
// levels reached, then on to `total` at the slope of the last interval; one level reached: a step there;
// none (smoke thinner than the first level): a step at `thinDepth`. Before the first knot 0, past the last
// its opacity.
struct OpacityCurve {
  float depth[6], opacity[6];
  int count;
};

OpacityCurve opacityCurve(vec4 depths, float total, float thinDepth) {
  OpacityCurve c;
  c.count = 0;
  if (total <= 0.0) return c;
  if (depths.x < 0.0) {
    c.depth[0] = c.depth[1] = thinDepth;
    c.opacity[0] = 0.0;
    c.opacity[1] = total;
    c.count = 2;
    return c;
  }
  int reached = 1;
  while (reached < 4 && depths[reached] >= 0.0) ++reached;
  c.depth[0] = reached > 1 ? depths.x - 0.4 * (depths.y - depths.x) : depths.x;
  c.opacity[0] = 0.0;
  for (int k = 0; k < reached; ++k) {
    c.depth[k + 1] = depths[k];
    c.opacity[k + 1] = kOpacityLevels[k];
  }
  int last = reached - 1;
  float slope = reached > 1
                    ? (depths[last] - depths[last - 1]) / (kOpacityLevels[last] - kOpacityLevels[last - 1])
                    : 0.0;
  float rest = max(total - kOpacityLevels[last], 0.0);
  c.depth[reached + 1] = depths[last] + rest * slope;
  c.opacity[reached + 1] = kOpacityLevels[last] + rest;
  c.count = reached + 2;
  return c;
}

// ∫ over (−∞, d] of the curve's opacity (exact: trapezoids).
float opacityIntegral(OpacityCurve c, float d) {
  if (c.count == 0 || d <= c.depth[0]) return 0.0;
  float sum = 0.0;
  for (int i = 1; i < c.count; ++i) {
    float d0 = c.depth[i - 1], d1 = c.depth[i];
    if (d <= d1) {
      float t = d1 > d0 ? (d - d0) / (d1 - d0) : 1.0;
      return sum + (d - d0) * (c.opacity[i - 1] + 0.5 * t * (c.opacity[i] - c.opacity[i - 1]));
    }
    sum += (d1 - d0) * 0.5 * (c.opacity[i - 1] + c.opacity[i]);
  }
  return sum + (d - c.depth[c.count - 1]) * c.opacity[c.count - 1];
}

// The opacity in front of view depth d, averaged over [d − w, d + w] (w > 0): the guide resolves depth no
// finer than its texel, so a smoke front between texel centres is as likely a little nearer or farther, and a
// step of the curve becomes a ramp 2w deep instead of a contour cut into whatever it meets.
float opacityInFront(OpacityCurve c, float d, float w) {
  if (c.count == 0 || d + w <= c.depth[0]) return 0.0;
  if (d - w >= c.depth[c.count - 1])
    return c.opacity[c.count - 1];  // also for d far beyond, without rounding
  return (opacityIntegral(c, d + w) - opacityIntegral(c, d - w)) / (2.0 * w);
}

// A depth-buffer value back to view depth. Every perspective projection into Vulkan's clip space stores
// d = offset + scale / v (render::DepthMapping: standard, reversed-Z, infinite far), so v = scale / (d − offset);
// a value at or beyond the far end (a cleared infinite reversed-Z buffer, d = offset) is infinitely far. The
// offset comes as a float and its rounding error (`offsetRest`): far away in standard depth d ≈ offset ≈ 1, and
// d − offset, exact in float there (Sterbenz), would otherwise carry the offset's rounding as a relative error
// of 1e-6 in v.
float viewDepthFromDepthBuffer(float d, float offset, float offsetRest, float scale) {
  precise float denominator = (d - offset) - offsetRest;
  return denominator * scale > 0.0 ? scale / denominator : 1e30;
}

// The world point at view depth `viewDepth` behind image-plane point `q` (the plane at distance 1, x right,
// y up, as in CameraRays.plane).
vec3 worldAtViewDepth(CameraRays c, vec2 q, float viewDepth) {
  return c.position.xyz + viewDepth * (c.forward.xyz + q.x * c.right.xyz + q.y * c.up.xyz);
}

#endif
