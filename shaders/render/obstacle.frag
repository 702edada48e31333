#version 460
// Lambertian obstacles (docs/real-time-rendering.md, "Obstacles and shadows"): the scene lights, directional
// (irradiance = intensity) and point (intensity / r²), each shadowed by the obstacles through its shadow map,
// plus the ambient radiance L0 + L1·w, whose cosine integral over the hemisphere of n gives the outgoing
// radiance albedo·(L0 + (2/3) L1·n). Two-sided: the normal is turned toward the viewer's side of the
// triangle (open meshes, inconsistent windings). Output is premultiplied with alpha 1.
// The smoke shadows the obstacles (docs/real-time-rendering.md, "Smoke and obstacles"): each light by the
// smoke's optical depth from the surface point toward it (the direct light e^{−τ}, plus what a slab of that
// depth scatters on toward the surface, scatteredThrough), the ambient light likewise along the normal; each
// depth a march of half-cell midpoint steps through the density (the volume of the recorded frame).
#extension GL_GOOGLE_include_directive : require
#include "obstacle_params.glsl"
#include "shadow.glsl"
#include "volume.glsl"

layout(binding = 2) uniform sampler2D shadowAtlas;
layout(std430, binding = 3) readonly buffer Density {
  float density[];
};
layout(push_constant) uniform ObstaclePush {
  VolumeGrid smoke;  // size 0: no smoke
  vec4 optics;  // x: extinction per unit density; y: single-scattering albedo ω; z: Henyey–Greenstein g
}
push;

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

const int kMaxSmokeSteps = 1024;

// The smoke's optical depth from p along unit w (up to tMax), by half-cell midpoint steps.
float smokeDepth(vec3 p, vec3 w, float tMax) {
  if (push.smoke.size.x == 0) return 0.0;
  vec2 span = rayBox(p, safeInverse(w), volumeBoxMin(push.smoke), volumeBoxMax(push.smoke));
  span.y = min(span.y, tMax);
  if (span.x >= span.y) return 0.0;
  float step = 0.5 * push.smoke.originCell.w;
  int steps = min(kMaxSmokeSteps, int(ceil((span.y - span.x) / step)));
  step = (span.y - span.x) / float(steps);
  float tau = 0.0;
  for (int i = 0; i < steps; ++i) {
    Lerp8 l =
        lerp8(push.smoke.size.xyz, volumeSampleCoord(push.smoke, p + (span.x + (float(i) + 0.5) * step) * w));
    tau += max(0.0, LERP8(density, l));
  }
  return push.optics.x * tau * step;
}

// The light that a slab of smoke of optical depth τ lets through diffusely (scattered, not counting the
// direct e^{−τ}): the hemispheric-mean two-stream transmission of a homogeneous slab under diffuse light
// (Meador & Weaver 1980), T = k / (k cosh kτ + γ1 sinh kτ) with γ1 = 2 − ω(1 + g), γ2 = ω(1 − g), k = √(γ1² −
// γ2²), less e^{−τ}.
float scatteredThrough(float tau) {
  float omega = push.optics.y, g = push.optics.z;
  float g1 = 2.0 - omega * (1.0 + g), g2 = omega * (1.0 - g), k = sqrt(max(g1 * g1 - g2 * g2, 1e-8));
  float kt = min(k * tau, 40.0);
  float total = k / (k * cosh(kt) + g1 * sinh(kt));
  return max(total - exp(-tau), 0.0);
}

void main() {
  vec3 n = normalize(worldNormal);
  vec3 facet = cross(dFdx(worldPosition), dFdy(worldPosition));
  if (dot(facet, params.eye.xyz - worldPosition) < 0.0) facet = -facet;
  if (dot(n, facet) < 0.0) n = -n;

  // The smoke's marches start a cell off the surface: the cells at an obstacle's face hold the grid's blur of
  // the face itself, and a ray along the face through them would see smoke that the face's own light never
  // crosses.
  vec3 lifted = worldPosition + push.smoke.originCell.w * n;
  vec3 irradiance = vec3(0.0);
  for (int i = 0; i < int(params.albedo.w); ++i) {
    vec4 light = params.lightVector[i];
    vec3 toLight = light.xyz - light.w * worldPosition;
    float falloff = light.w > 0.0 ? 1.0 / dot(toLight, toLight) : 1.0;
    vec3 l = normalize(toLight);
    float cosine = dot(n, l);
    // Through the smoke: the direct light e^{−τ} at the cosine, and the light the smoke scatters on toward
    // the surface, arriving diffusely from the light's side ((1 + n·l)/2 of it on a surface turned by n; none
    // without smoke).
    float tau = smokeDepth(lifted, l, light.w > 0.0 ? length(toLight) : 3.4e38);
    float through = max(cosine, 0.0) * exp(-tau) + 0.5 * (1.0 + cosine) * scatteredThrough(tau);
    if (through <= 0.0) continue;
    float visibility = lightVisibility(i, worldPosition, n, l);
    irradiance += params.lightIntensity[i].rgb * (falloff * visibility * through);
  }
  vec3 ambient =
      params.ambient[0].rgb +
      (2.0 / 3.0) * (n.x * params.ambient[1].rgb + n.y * params.ambient[2].rgb + n.z * params.ambient[3].rgb);
  if (any(greaterThan(ambient, vec3(0.0)))) {
    float tau = smokeDepth(lifted, n, 3.4e38);
    ambient *= exp(-tau) + scatteredThrough(tau);
  }
  color = vec4(params.albedo.rgb * (irradiance / PI + max(ambient, vec3(0.0))), 1.0);
}
