#version 460
// Lambertian obstacles (docs/real-time-rendering.md, "Obstacles and shadows"): the scene lights, directional
// (irradiance = intensity) and point (intensity / r²), each shadowed by the obstacles through its shadow map,
// plus the ambient radiance L0 + L1·w, whose cosine integral over the hemisphere of n gives the outgoing
// radiance albedo·(L0 + (2/3) L1·n). Two-sided: the normal is turned toward the viewer's side of the
// triangle (open meshes, inconsistent windings). Output is premultiplied with alpha 1.
#extension GL_GOOGLE_include_directive : require
#include "obstacle_params.glsl"
#include "shadow.glsl"

layout(binding = 2) uniform sampler2D shadowAtlas;

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 0) out vec4 color;

const float PI = 3.14159265358979;
const float PCF_RADIUS = 1.0;  // texels

// The lit fraction of the surface point `p` with normal `n` for light `i`. Against shadow acne, the point
// looked up is moved off the surface by texel sizes at its distance: along the normal by the filter radius
// plus 1.5 (a tilted surface's depth changes by up to a texel per texel), and one toward the light.
float lightVisibility(int i, vec3 p, vec3 n, vec3 towardLight) {
  int tile = int(params.lightShadow[i].x);
  if (tile < 0) return 1.0;
  mat4 lightViewProjection = params.lightViewProjection[i];
  float texel = params.lightShadow[i].y * (lightViewProjection * vec4(p, 1.0)).w;
  vec3 lifted = p + texel * ((PCF_RADIUS + 1.5) * n + towardLight);
  return shadowVisibility(shadowAtlas, tile, int(params.eye.w), lightViewProjection, lifted, PCF_RADIUS, 0.0);
}

void main() {
  vec3 n = normalize(worldNormal);
  vec3 facet = cross(dFdx(worldPosition), dFdy(worldPosition));
  if (dot(facet, params.eye.xyz - worldPosition) < 0.0) facet = -facet;
  if (dot(n, facet) < 0.0) n = -n;

  vec3 irradiance = vec3(0.0);
  for (int i = 0; i < int(params.albedo.w); ++i) {
    vec4 light = params.lightVector[i];
    vec3 toLight = light.xyz - light.w * worldPosition;
    float falloff = light.w > 0.0 ? 1.0 / dot(toLight, toLight) : 1.0;
    vec3 l = normalize(toLight);
    float cosine = dot(n, l);
    if (cosine <= 0.0) continue;
    irradiance += params.lightIntensity[i].rgb * (falloff * cosine * lightVisibility(i, worldPosition, n, l));
  }
  vec3 ambient = params.ambient[0].rgb + (2.0 / 3.0) * (n.x * params.ambient[1].rgb + n.y * params.ambient[2].rgb +
                                                        n.z * params.ambient[3].rgb);
  color = vec4(params.albedo.rgb * (irradiance / PI + max(ambient, vec3(0.0))), 1.0);
}
