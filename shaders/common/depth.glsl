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

// The opacity of the smoke in front of view depth d, of a ray whose opacity reaches `total` and the levels at
// `depths` (< 0: not reached): linear in depth between the levels; before the first, from 0 over a quarter of
// its distance to the second (or nothing); past the last reached, the rest (total − its level) over the
// distance the last interval took per unit of opacity. Smoke too thin to reach the first level lies at
// `thinDepth`.
float opacityInFront(vec4 depths, float total, float d, float thinDepth) {
  if (total <= 0.0) return 0.0;
  if (depths.x < 0.0) return d >= thinDepth ? total : 0.0;
  float before =
      depths.y >= 0.0 ? 0.4 * (depths.y - depths.x) : 0.0;  // 0.1 of the 0.25 between the first two
  if (d <= depths.x)
    return before > 0.0 ? kOpacityLevels[0] * clamp(1.0 - (depths.x - d) / before, 0.0, 1.0) : 0.0;
  float perOpacity = before / kOpacityLevels[0];  // depth per unit of opacity, of the last interval
  for (int k = 1; k < 4; ++k) {
    if (depths[k] < 0.0) {
      float rest = max(total - kOpacityLevels[k - 1], 0.0);
      float width = rest * perOpacity;
      return kOpacityLevels[k - 1] +
             (width > 0.0 ? rest * clamp((d - depths[k - 1]) / width, 0.0, 1.0) : rest);
    }
    perOpacity = (depths[k] - depths[k - 1]) / (kOpacityLevels[k] - kOpacityLevels[k - 1]);
    if (d <= depths[k])
      return mix(kOpacityLevels[k - 1], kOpacityLevels[k],
                 (d - depths[k - 1]) / max(depths[k] - depths[k - 1], 1e-9));
  }
  float rest = max(total - kOpacityLevels[3], 0.0), width = rest * perOpacity;
  return kOpacityLevels[3] + (width > 0.0 ? rest * clamp((d - depths.w) / width, 0.0, 1.0) : rest);
}

// A depth-buffer value of render::projectionMatrix(plane, {near, far}) back to view depth:
// d = far (z − near) / (z (far − near))  ⇔  z = near far / (far − d (far − near)).
float viewDepthFromDepthBuffer(float d, vec2 range) {
  return range.x * range.y / (range.y - d * (range.y - range.x));
}

// The world point at view depth `viewDepth` behind image-plane point `q` (the plane at distance 1, x right,
// y up, as in CameraRays.plane).
vec3 worldAtViewDepth(CameraRays c, vec2 q, float viewDepth) {
  return c.position.xyz + viewDepth * (c.forward.xyz + q.x * c.right.xyz + q.y * c.up.xyz);
}

#endif
