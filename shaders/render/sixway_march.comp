#version 460
// The eight six-way channels by a fine view-ray march (single scattering, no noise): for each pixel of the
// billboard, the ray from the camera is clipped to the volume's box and cut into equal steps no longer than
// the step limit; each step is a slab of constant σ_t (the density at its midpoint), which absorbs
// T·(1 − e^{−σ_t Δ}) of the light passing through and scatters toward the camera, for each light i,
//   L_i += T·(1 − e^{−σ_t Δ}) · albedo · π · p_HG(d_i·ω) · e^{−τ_i},
// light of irradiance π arriving from direction d_i with the optical depth τ_i of its light grid
// (light_depth.comp). alpha = 1 − T at the end of the ray, and the emission is
//   E += T·(1 − e^{−σ_t Δ}) · (intensity / extinction) · luminance(ramp(temperature)),
// the exact integral over the slab of the emitted radiance intensity · density · ramp. Steps inside empty
// bricks (majorant.comp) are skipped: their density is exactly zero, so the sum is the same.
#extension GL_GOOGLE_include_directive : require
#define BAKE_PARAMS_IN_STORAGE
#include "bake_params.glsl"
#include "phase.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 1) readonly buffer Density { float density[]; };
layout(std430, binding = 2) readonly buffer Temperature { float temperature[]; };
layout(std430, binding = 3) readonly buffer Majorants { float brickMax[]; };
layout(std430, binding = 4) readonly buffer Depth0 { float depth0[]; };
layout(std430, binding = 5) readonly buffer Depth1 { float depth1[]; };
layout(std430, binding = 6) readonly buffer Depth2 { float depth2[]; };
layout(std430, binding = 7) readonly buffer Depth3 { float depth3[]; };
layout(std430, binding = 8) readonly buffer Depth4 { float depth4[]; };
layout(std430, binding = 9) readonly buffer Depth5 { float depth5[]; };
layout(std430, binding = 10) writeonly buffer Lightmaps { float lightmaps[]; };  // channel-planar, 8 channels

// 1 − e^{−x} without the cancellation of small x.
float oneMinusExp(float x) {
  return x < 1e-3 ? x * (1.0 - x * (0.5 - x / 6.0)) : 1.0 - exp(-x);
}

// Optical depth toward light i at p, interpolated on its light grid.
float lightDepth(int i, vec3 p) {
  LightGrid g = params.lights[i];
  Lerp8 n = lerp8(g.nodes.xyz, lightGridCoord(g, p));
  switch (i) {
    case 0: return LERP8(depth0, n);
    case 1: return LERP8(depth1, n);
    case 2: return LERP8(depth2, n);
    case 3: return LERP8(depth3, n);
    case 4: return LERP8(depth4, n);
    default: return LERP8(depth5, n);
  }
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = params.image.xy;
  if (any(greaterThanEqual(pixel, size))) return;
  vec3 origin = params.camera.position.xyz;
  vec3 dir = cameraRayDirection(params.camera, vec2(pixel) + 0.5, vec2(size));
  vec3 invDir = safeInverse(dir);
  vec3 boxMin = volumeBoxMin(params.volume);
  vec2 span = rayBox(origin, invDir, boxMin, volumeBoxMax(params.volume));
  const bool emissive = params.image.z > 0;
  const float extinction = params.optics.x;
  const float brickSize = float(params.bricks.w) * params.volume.originCell.w;
  // The angle between a light's and the view's propagation directions is the same all along the ray.
  float scatter[6];
  for (int i = 0; i < 6; ++i)
    scatter[i] = params.optics.y * kPi * hgPhase(dot(params.lights[i].toLight.xyz, dir), params.optics.z);

  float transmittance = 1.0, emitted = 0.0;
  float radiance[6] = float[6](0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
  if (span.x < span.y) {
    int steps = int(ceil((span.y - span.x) / params.march.x));
    float dt = (span.y - span.x) / float(steps);
    for (int i = 0; i < steps && transmittance > params.march.y; ++i) {
      vec3 p = origin + (span.x + (float(i) + 0.5) * dt) * dir;
      ivec3 b = clamp(ivec3(floor((p - boxMin) / brickSize)), ivec3(0), params.bricks.xyz - 1);
      if (brickMax[(b.z * params.bricks.y + b.y) * params.bricks.x + b.x] <= 0.0) {
        // Jump to the last step inside this brick (the loop's ++i moves past it).
        vec3 lo = boxMin + vec3(b) * brickSize;
        vec3 far = max((lo - origin) * invDir, (lo + brickSize - origin) * invDir);
        float exit = min(far.x, min(far.y, far.z)) - 1e-4 * brickSize;
        i = max(i, int(floor((exit - span.x) / dt - 0.5)));
        continue;
      }
      Lerp8 l = lerp8(params.volume.size.xyz, volumeSampleCoord(params.volume, p));
      float sigma = extinction * max(0.0, LERP8(density, l));
      if (sigma <= 0.0) continue;
      float segment = exp(-sigma * dt);
      float absorbed = transmittance * oneMinusExp(sigma * dt);
      for (int light = 0; light < 6; ++light) radiance[light] += absorbed * scatter[light] * exp(-lightDepth(light, p));
      if (emissive) {
        float t = params.image.w != 0 ? LERP8(temperature, l) : 0.0;
        emitted += absorbed * (params.optics.w / extinction) * luminance(rampColor(params.image.z, t));
      }
      transmittance *= segment;
    }
  }
  uint plane = uint(size.x * size.y), index = uint(pixel.y * size.x + pixel.x);
  for (int light = 0; light < 6; ++light) lightmaps[uint(light) * plane + index] = radiance[light];
  lightmaps[6u * plane + index] = 1.0 - transmittance;
  lightmaps[7u * plane + index] = emitted;
}
