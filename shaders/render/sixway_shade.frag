#version 460
// Six-way shading of the smoke billboard (docs/conventions.md, "Shading"; docs/real-time-rendering.md,
// "Six-way shading"), drawn with premultiplied-over blending onto the background and the obstacles. Per
// pixel: the lightmaps at the pixel's point of the billboard (bilinear), Unity's remapping controls, every
// light with squared six-way weights (point lights toward the shaded point, inverse-square falloff), its
// obstacle shadow (PCF in the shadow atlas at the smoke shell), ambient light from L1 spherical harmonics,
// the emissive gradient. Where an obstacle lies nearer than the smoke, the smoke is hidden.
#extension GL_GOOGLE_include_directive : require
#include "depth.glsl"
#include "shadow.glsl"
#include "sixway_shade_params.glsl"

layout(binding = 2) uniform sampler2D lightmapA;  // R Right, G Top, B Back, A alpha (linear, premultiplied)
layout(binding = 3) uniform sampler2D lightmapB;  // R Left, G Bottom, B Front, A emissive
layout(binding = 4) uniform sampler2D guide;      // B: encoded shell depth (1: no shell); see depth.glsl
layout(binding = 5) uniform sampler2D obstacleDepth;  // the obstacles' depth buffer, the whole frame
layout(binding = 6) uniform sampler2D shadowAtlas;    // shadow.glsl

layout(location = 0) out vec4 outColor;

void main() {
  // The pixel's point of the image plane (the frame covers params.camera.plane; row 0 at the top).
  vec2 frameUv = gl_FragCoord.xy / vec2(push.frame.xy);
  vec4 plane = params.camera.plane;
  vec2 q = vec2(mix(plane.x, plane.z, frameUv.x), mix(plane.w, plane.y, frameUv.y));
  vec2 uv = frameUv * params.frameToBillboard.xy + params.frameToBillboard.zw;

  // The shaded point: the smoke shell where the pixel has one, else the billboard's plane.
  float viewDepth = interpolatedShadedDepth(guide, uv, params.depths.xy, params.misc.x);
  if (push.frame.z != 0) {
    float obstacle = viewDepthFromDepthBuffer(texelFetch(obstacleDepth, ivec2(gl_FragCoord.xy), 0).r,
                                              params.depths.zw);
    if (obstacle < viewDepth) {  // the obstacle hides the smoke
      outColor = vec4(0.0);
      return;
    }
  }
  vec3 world = worldAtViewDepth(params.camera, q, viewDepth);

  vec4 a = texture(lightmapA, uv), b = texture(lightmapB, uv);
  vec3 rightTopBack = a.rgb, leftBottomFront = b.rgb;
  float alpha = a.a, emissive = b.a;
  int flags = params.counts.z;
  if ((flags & 2) != 0 && alpha > 0.0) {  // remap straight values, then premultiply again
    rightTopBack = alpha * remapRange(rightTopBack / alpha, params.lightmapRemap);
    leftBottomFront = alpha * remapRange(leftBottomFront / alpha, params.lightmapRemap);
  }
  if ((flags & 4) != 0) {  // new opacity: every premultiplied channel follows it
    float remapped = clamp(remapRange(vec3(alpha), params.alphaRemap).x, 0.0, 1.0);
    float scale = alpha > 0.0 ? remapped / alpha : 0.0;
    rightTopBack *= scale;
    leftBottomFront *= scale;
    emissive *= scale;
    alpha = remapped;
  }

  bool absorption = (flags & 1) != 0;
  vec3 color = params.color.rgb;
  float range = params.color.w;
  vec3 right = params.camera.right.xyz, up = params.camera.up.xyz, forward = params.camera.forward.xyz;
  vec3 radiance = vec3(0.0);
  for (int i = 0; i < params.counts.x; ++i) {
    vec3 toLight = lights[i].vector.xyz;
    vec3 irradiance = lights[i].radiance.rgb;
    if (lights[i].vector.w != 0.0) {  // point light: toward it from the shaded point, 1/r² falloff
      toLight -= world;
      float r2 = max(dot(toLight, toLight), 1e-12);
      irradiance /= r2;
      toLight *= inversesqrt(r2);
    }
    int tile = int(lights[i].radiance.w);
    float visibility = 1.0;
    if (tile >= 0 && tile < push.atlas.y && push.atlas.x > 0)
      visibility = shadowVisibility(shadowAtlas, tile, push.atlas.x, lights[i].shadowMatrix, world,
                                    push.shadow.x, push.shadow.y);
    vec3 d = vec3(dot(toLight, right), dot(toLight, up), dot(toLight, forward));
    float t = sixWayTransmission(d, rightTopBack, leftBottomFront);
    radiance += (visibility / kPi) * irradiance * lightResponse(t, alpha, color, range, absorption);
  }
  radiance += sixWayAmbient(rightTopBack, leftBottomFront, params.ambient, alpha, color, range, absorption);
  // Emission (docs/real-time-rendering.md, "Emission"): Unity's gradient of the channel, or, with a straight
  // scale s, the gradient at the straight value e / (alpha s) times alpha s: the hue of the smoke's temperature.
  float straight = params.misc.z;
  vec3 emission = straight > 0.0 ? (alpha > 0.0 ? alpha * straight *
                                                      gradientColor(params.gradient, params.counts.y,
                                                                    emissive / (alpha * straight))
                                                : vec3(0.0))
                                 : gradientColor(params.gradient, params.counts.y, emissive);
  radiance += params.misc.y * emission;
  outColor = vec4(radiance, alpha);
}
