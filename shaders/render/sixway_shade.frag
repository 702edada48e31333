#version 460
// Six-way shading of the smoke billboard (docs/conventions.md, "Shading"; docs/real-time-rendering.md,
// "Six-way shading"), drawn with premultiplied-over blending onto the background and the obstacles. Per
// pixel: the lightmaps at the pixel's point of the billboard (Catmull-Rom cubic, catmull_rom.glsl), Unity's
// remapping controls, every light with squared six-way weights (point lights toward the shaded point,
// inverse-square falloff), its obstacle shadow, ambient light from L1 spherical harmonics, the emissive
// gradient. Against the obstacles the smoke is a volume, not a card (docs/real-time-rendering.md, "Smoke and
// obstacles"): its opacity builds up over depth as the guide's opacity depths say (depth.glsl), the share of
// it in front of the obstacle is drawn and the rest hidden, and each light's obstacle shadow is the mean over
// the depths where the opacity reaches 0.1, 0.35 and 0.6 (in front of the obstacle); both are filtered over a
// lightmap texel's width, the finest detail the smoke's lightmaps hold.
#extension GL_GOOGLE_include_directive : require
#include "catmull_rom.glsl"
#include "depth.glsl"
#include "shadow.glsl"
#include "sixway_shade_params.glsl"

layout(binding = 2) uniform sampler2D lightmapA;  // R Right, G Top, B Back, A alpha (linear, premultiplied)
layout(binding = 3) uniform sampler2D lightmapB;  // R Left, G Bottom, B Front, A emissive
layout(binding = 4) uniform sampler2D guide;      // B: encoded shell depth (1: no shell); see depth.glsl
layout(binding = 5) uniform sampler2D obstacleDepth;  // the obstacles' depth buffer, the whole frame
layout(binding = 6) uniform sampler2D shadowAtlas;    // shadow.glsl
layout(binding = 7) uniform sampler2D opacityDepths;  // where the smoke's opacity builds up; see depth.glsl

layout(location = 0) out vec4 outColor;

void main() {
  // The pixel's point of the image plane (the viewport covers params.camera.plane; row 0 at the top).
  vec2 frameUv = (gl_FragCoord.xy - vec2(push.viewport.xy)) / vec2(push.viewport.zw);
  vec4 plane = params.camera.plane;
  vec2 q = vec2(mix(plane.x, plane.z, frameUv.x), mix(plane.w, plane.y, frameUv.y));
  vec2 uv = frameUv * params.frameToBillboard.xy + params.frameToBillboard.zw;
  // A lightmap texel's width in the world per unit of view depth: the finest detail the smoke's lightmaps,
  // guide and opacity depths resolve, which sets how soft its contacts with obstacles and their shadows are.
  float texelPerDepth = (plane.z - plane.x) / params.frameToBillboard.x / float(textureSize(lightmapA, 0).x);

  // The shaded point: the smoke shell where the pixel has one, else the billboard's plane.
  float viewDepth = interpolatedShadedDepth(guide, uv, params.depths.xy, params.misc.x);
  float obstacle =
      push.frame.z != 0
          ? viewDepthFromDepthBuffer(texelFetch(obstacleDepth, ivec2(gl_FragCoord.xy), 0).r, params.depths.z,
                                     params.misc.w, params.depths.w)
          : 3.4e38;
  // `visible`: the share of the smoke's opacity in front of the obstacle, bilinear over the four nearest
  // guide texels' own shares; `shadowDepths`: the depths where the opacity reaches 0.1, 0.35, 0.6,
  // interpolated alike (a level a texel does not reach: its last one reached, or the billboard's plane), in
  // front of the obstacle. Without opacity depths the smoke is a card at the shell.
  float visible = float(obstacle >= viewDepth);
  vec3 shadowDepths = vec3(viewDepth);
  if (push.frame.w != 0) {
    ivec2 size = textureSize(opacityDepths, 0);
    vec2 g = uv * vec2(size) - 0.5;
    ivec2 base = ivec2(floor(g));
    vec2 f = g - vec2(base);
    float texelWidth = texelPerDepth * min(obstacle, 1e6);
    visible = 0.0;
    shadowDepths = vec3(0.0);
    for (int k = 0; k < 4; ++k) {
      ivec2 texel = clamp(base + ivec2(k & 1, k >> 1), ivec2(0), size - 1);
      vec2 w2 = mix(1.0 - f, f, vec2(k & 1, k >> 1));
      vec4 encoded = texelFetch(opacityDepths, texel, 0);
      vec4 levels;
      for (int i = 0; i < 4; ++i)
        levels[i] = encoded[i] < 1.0 ? decodeShellDepth(encoded[i], params.depths.xy) : -1.0;
      vec4 g4 = texelFetch(guide, texel, 0);
      float total = g4.a > 0.0 ? g4.a : g4.g;  // the fine alpha where the guide has it
      float share =
          total > 0.0
              ? min(opacityInFront(opacityCurve(levels, total, params.misc.x), obstacle, texelWidth) / total,
                    1.0)
              : 1.0;
      visible += w2.x * w2.y * share;
      float last = params.misc.x;
      for (int i = 0; i < 3; ++i) {
        if (levels[i] >= 0.0) last = levels[i];
        shadowDepths[i] += w2.x * w2.y * last;
      }
    }
  }
  if (visible <= 0.0) {  // the obstacle hides all of the smoke
    outColor = vec4(0.0);
    return;
  }
  viewDepth = min(viewDepth, obstacle);
  vec3 world = worldAtViewDepth(params.camera, q, viewDepth);
  vec3 shadowPoints[3];
  for (int i = 0; i < 3; ++i)
    shadowPoints[i] = worldAtViewDepth(params.camera, q, min(shadowDepths[i], obstacle));

  // The cubic's overshoot clamped: light and emission not below 0, alpha within [0, 1].
  vec4 a = clamp(textureCatmullRom(lightmapA, uv), vec4(0.0), vec4(vec3(3.4e38), 1.0));
  vec4 b = max(textureCatmullRom(lightmapB, uv), vec4(0.0));
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
    if (tile >= 0 && tile < push.atlas.y && push.atlas.x > 0) {
      visibility = 0.0;
      for (int k = 0; k < 3; ++k)
        visibility += wideShadowVisibility(shadowAtlas, tile, push.atlas.x, lights[i].shadowMatrix,
                                           shadowPoints[k], texelPerDepth * min(shadowDepths[k], obstacle),
                                           push.shadow.x, push.shadow.y) /
                      3.0;
    }
    vec3 d = vec3(dot(toLight, right), dot(toLight, up), dot(toLight, forward));
    float t = sixWayTransmission(d, rightTopBack, leftBottomFront);
    radiance += (visibility / kPi) * irradiance * lightResponse(t, alpha, color, range, absorption);
  }
  radiance += sixWayAmbient(rightTopBack, leftBottomFront, params.ambient, alpha, color, range, absorption);
  // Emission (docs/real-time-rendering.md, "Emission"): Unity's gradient of the channel, or, with a straight
  // scale s, the gradient at the straight value e / (alpha s) times alpha s: the hue of the smoke's
  // temperature.
  float straight = params.misc.z;
  vec3 emission =
      straight > 0.0
          ? (alpha > 0.0 ? alpha * straight *
                               gradientColor(params.gradient, params.counts.y, emissive / (alpha * straight))
                         : vec3(0.0))
          : gradientColor(params.gradient, params.counts.y, emissive);
  radiance += params.misc.y * emission;
  outColor = visible * vec4(radiance, alpha);
}
