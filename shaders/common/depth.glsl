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
float decodeShellDepth(float encoded, vec2 range) { return mix(range.x, range.y, encoded); }

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
