#version 460
// The guiding map (docs/real-time-rendering.md, "Guiding map"): one coarse, jittered view-ray march per pixel
// of the billboard. The ray is clipped to the volume's box; its samples lie at t = entry + (u + i)·h with
// h the coarse step and u in [0, 1) one hash per pixel and frame, so over frames the sum below is an
// unbiased estimate of the ray integral. Each sample stands for a slab of length h and constant σ_t, which
// takes T·(1 − e^{−σ_t h}) out of the view transmittance T and scatters toward the camera, in the bake
// normalisation (docs/conventions.md, "Bake normalisation": light of irradiance π, albedo, Henyey–Greenstein
// phase):
//   front light:  π p_HG · albedo · T² (1 − e^{−2 σ_t h}) / 2  (its path is the view path; exact in the slab)
//   other lights: π p_HG · albedo · T (1 − e^{−σ_t h}) · e^{−τ_i}
// with τ_i the optical depth toward light i from a coarse light grid (light_depth.comp).
// Opposite lights share a grid: the optical depth toward the far end of a column is its total minus the
// depth toward the near end, so e.g. top's grid also serves bottom.
// Output (RGBA16F): R = the sum over the guide lights, G = alpha = 1 − T, B = the encoded view depth where
// alpha first reaches the shell threshold (exact within the slab; 1 where it never does), A = 0, or with
// kFineAlpha the alpha of a second, fine march (step march.z, midpoints, not jittered: the baker's alpha
// quadrature), an input the network need not guess. With kEmission the same fine march also
// integrates the direct emission toward the camera into a second image, as the exact baker's emissive channel
// does (sixway_march.comp): E += T·(1 − e^{−σ_t Δ})·(intensity / extinction)·luminance(ramp(temperature));
// the network learns the scattered glow from it (docs/network-study.md, "Emission in the guide"). A second
// image (RGBA16F) holds how the smoke's opacity builds up along the ray, for the composite with obstacles
// (sixway_shade.frag): the view depths where the ray's opacity 1 − T first reaches each of kOpacityLevels
// (depth.glsl), exact within a slab as the shell depth is and encoded as it is; 1 where a level is not
// reached. With kFineAlpha from the fine march's steps (not jittered: no noise from frame to frame or pixel
// to pixel), else from the coarse march's. Samples in empty bricks (majorant.comp) are skipped without moving
// the sample lattice: same sums.
#extension GL_GOOGLE_include_directive : require
#define BAKE_PARAMS_IN_STORAGE
#include "bake_params.glsl"
#include "depth.glsl"
#include "phase.glsl"
#include "random.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int kShadowedLights = 1;  // guide lights other than front, ≤ 5
layout(constant_id = 1) const bool kFrontLight = true;  // whether the front light is a guide light
// Per guide light k other than front, bits 3k and 3k + 1: its light grid (the index into params.lights);
// bit 3k + 2: the light lies at the grid's far end. Constants, so that after unrolling the loop over lights
// every grid choice below is resolved at compile time.
layout(constant_id = 2) const int kLightGrids = 0;
layout(constant_id = 3) const bool kFineAlpha = false;
layout(constant_id = 4) const bool kEmission = false;  // only with kFineAlpha

// Per-frame values besides BakeParams (whose lights[] hold the light grids, at most one per axis, march.x the
// step and march.y the transmittance below which a ray stops once its shell depth is known).
layout(std430, binding = 1) readonly buffer GuideFrame {
  uvec4 jitter;  // x: seed, y: frame
  vec4 shell;    // x: opacity threshold, y, z: near and far view depths of the encoding
}
frame;
layout(std430, binding = 2) readonly buffer Density {
  float density[];
};
layout(std430, binding = 3) readonly buffer Majorants {
  float brickMax[];
};
layout(std430, binding = 4) readonly buffer Depth0 {
  float depth0[];
};
layout(std430, binding = 5) readonly buffer Depth1 {
  float depth1[];
};
layout(std430, binding = 6) readonly buffer Depth2 {
  float depth2[];
};
layout(binding = 7, rgba16f) uniform writeonly image2D guide;
layout(std430, binding = 8) readonly buffer Temperature {
  float temperature[];
};
layout(binding = 9, r32f) uniform writeonly image2D emission;  // written with kEmission
layout(binding = 10, rgba16f) uniform writeonly image2D opacityDepths;

// 1 − e^{−x} without the cancellation of small x.
float oneMinusExp(float x) {
  return x < 1e-3 ? x * (1.0 - x * (0.5 - x / 6.0)) : 1.0 - exp(-x);
}

int gridOf(int k) {
  return (kLightGrids >> (3 * k)) & 3;
}
bool atFarEnd(int k) {
  return ((kLightGrids >> (3 * k + 2)) & 1) != 0;
}

// Light grid i's optical depth, interpolated at n.
float gridDepth(int i, Lerp8 n) {
  switch (i) {
    case 0:
      return LERP8(depth0, n);
    case 1:
      return LERP8(depth1, n);
    default:
      return LERP8(depth2, n);
  }
}

// Optical depth toward guide light k (other than front) at p. For a light at its grid's far end: the whole
// column's (its last plane, with the same weights across the light) less the grid's.
float lightDepth(int k, vec3 p) {
  LightGrid g = params.lights[gridOf(k)];
  Lerp8 n = lerp8(g.nodes.xyz, lightGridCoord(g, p));
  float tau = gridDepth(gridOf(k), n);
  if (!atFarEnd(k)) return tau;
  uint plane = uint(g.nodes.x * g.nodes.y);
  Lerp8 column = n;
  column.base = n.base % plane + uint(g.nodes.z - 1) * plane;
  column.dz = 0u;
  return gridDepth(gridOf(k), column) - tau;
}

// Unit direction toward guide light k (other than front).
vec3 towardLight(int k) {
  vec3 d = params.lights[gridOf(k)].toLight.xyz;
  return atFarEnd(k) ? -d : d;
}

// The emitted luminance per unit optical depth at interpolation l: intensity · ramp / extinction, so that a
// slab absorbing a of the light passing through emits a times it (params.image.w: a temperature grid).
float emittedPerDepth(Lerp8 l) {
  float t = params.image.w != 0 ? LERP8(temperature, l) : 0.0;
  return (params.optics.w / params.optics.x) * luminance(rampColor(params.image.z, t));
}

// The view depths where the opacity 1 − T, T falling from `before` to `after` in a slab of extinction σ that
// starts at ray distance t, first reaches each level (T(s) = before·e^{−σ s} reaches 1 − level at s); levels
// already reached (< 0 in `depths`: not yet) keep theirs.
void crossLevels(inout vec4 depths, float before, float after, float sigma, float t, float slab,
                 float viewScale) {
  for (int k = 0; k < 4; ++k) {
    if (depths[k] >= 0.0 || 1.0 - after < kOpacityLevels[k]) continue;
    float s = clamp(log(before / (1.0 - kOpacityLevels[k])) / sigma, 0.0, slab);
    depths[k] = (t + s) * viewScale;
  }
}

// Along the ray through [span.x, span.y] by midpoint steps of length h (the last one shortened), empty bricks
// skipped, until T < 1e-4: x = 1 − T, y = the direct emission reaching the camera (with kEmission); `levels`
// (−1: not yet) gains the view depths where the opacity reaches kOpacityLevels.
vec2 fineMarch(vec3 origin, vec3 dir, vec3 invDir, vec3 boxMin, float brickSize, vec2 span, float h,
               float viewScale, inout vec4 levels) {
  float tau = 0.0, emitted = 0.0;
  const bool emits = kEmission && params.image.z > 0;  // no ramp keys: the smoke does not emit
  for (float t0 = span.x; t0 < span.y && tau < 9.2; t0 += h) {
    float dt = min(h, span.y - t0);
    vec3 p = origin + (t0 + 0.5 * dt) * dir;
    ivec3 b = clamp(ivec3(floor((p - boxMin) / brickSize)), ivec3(0), params.bricks.xyz - 1);
    if (brickMax[(b.z * params.bricks.y + b.y) * params.bricks.x + b.x] <= 0.0) {
      // On to the first step whose midpoint may lie past this empty brick.
      vec3 lo = boxMin + vec3(b) * brickSize;
      vec3 far = max((lo - origin) * invDir, (lo + brickSize - origin) * invDir);
      float exit = min(far.x, min(far.y, far.z));
      t0 += max(0.0, floor((exit - t0 - 0.5 * h) / h)) * h;
      continue;
    }
    Lerp8 l = lerp8(params.volume.size.xyz, volumeSampleCoord(params.volume, p));
    float sigma = params.optics.x * max(0.0, LERP8(density, l)), slab = sigma * dt;
    if (emits && slab > 0.0) emitted += exp(-tau) * oneMinusExp(slab) * emittedPerDepth(l);
    if (slab > 0.0) crossLevels(levels, exp(-tau), exp(-tau - slab), sigma, t0, dt, viewScale);
    tau += slab;
  }
  return vec2(oneMinusExp(tau), emitted);
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
  const float extinction = params.optics.x, h = params.march.x, threshold = frame.shell.x;
  const float brickSize = float(params.bricks.w) * params.volume.originCell.w;
  // The angle between a light's and the view's propagation directions is the same all along the ray.
  float albedoPi = params.optics.y * kPi;
  float frontScatter =
      kFrontLight ? 0.5 * albedoPi * hgPhase(-dot(params.camera.forward.xyz, dir), params.optics.z) : 0.0;
  float scatter[5];
  for (int k = 0; k < 5; ++k)
    scatter[k] = k < kShadowedLights ? albedoPi * hgPhase(dot(towardLight(k), dir), params.optics.z) : 0.0;

  float transmittance = 1.0, radiance = 0.0, shell = -1.0;  // shell < 0: the threshold is not reached yet
  vec4 levels = vec4(-1.0);  // the view depths where the opacity reaches kOpacityLevels; < 0: not yet
  const float viewScale = dot(dir, params.camera.forward.xyz);  // view depth per unit of t
  if (span.x < span.y) {
    uint state = rngSeed(frame.jitter.x, uint(pixel.y * size.x + pixel.x), frame.jitter.y);
    float u = rngNext(state);
    int samples = max(0, int(ceil((span.y - span.x) / h - u)));  // t < exit
    for (int i = 0; i < samples && (transmittance > params.march.y || shell < 0.0); ++i) {
      float t = span.x + (u + float(i)) * h;
      vec3 p = origin + t * dir;
      ivec3 b = clamp(ivec3(floor((p - boxMin) / brickSize)), ivec3(0), params.bricks.xyz - 1);
      if (brickMax[(b.z * params.bricks.y + b.y) * params.bricks.x + b.x] <= 0.0) {
        // Jump to the last sample inside this brick (the loop's ++i moves past it).
        vec3 lo = boxMin + vec3(b) * brickSize;
        vec3 far = max((lo - origin) * invDir, (lo + brickSize - origin) * invDir);
        float exit = min(far.x, min(far.y, far.z)) - 1e-4 * brickSize;
        i = max(i, int(floor((exit - span.x) / h - u)));
        continue;
      }
      Lerp8 l = lerp8(params.volume.size.xyz, volumeSampleCoord(params.volume, p));
      float sigma = extinction * max(0.0, LERP8(density, l));
      if (sigma <= 0.0) continue;
      float tau = sigma * h;
      float absorbed = transmittance * oneMinusExp(tau);
      float lit = frontScatter * transmittance * transmittance * oneMinusExp(2.0 * tau);
      for (int k = 0; k < kShadowedLights; ++k) lit += absorbed * scatter[k] * exp(-lightDepth(k, p));
      radiance += lit;
      float after = transmittance * exp(-tau);
      crossLevels(levels, transmittance, after, sigma, t - 0.5 * h, h, viewScale);
      if (shell < 0.0 && 1.0 - after >= threshold) {
        // Within the slab [t − h/2, t + h/2], T(s) = T·e^{−σ_t s} reaches 1 − threshold at s.
        float s = clamp(log(transmittance / (1.0 - threshold)) / sigma, 0.0, h);
        shell = (t - 0.5 * h + s) * dot(dir, params.camera.forward.xyz);
      }
      transmittance = after;
    }
  }
  float depth = shell < 0.0 ? 1.0 : encodeShellDepth(shell, frame.shell.yz);
  vec4 fineLevels = vec4(-1.0);
  vec2 fine = kFineAlpha && span.x < span.y ? fineMarch(origin, dir, invDir, boxMin, brickSize, span,
                                                        params.march.z, viewScale, fineLevels)
                                            : vec2(0.0);
  imageStore(guide, pixel, vec4(radiance, 1.0 - transmittance, depth, fine.x));
  if (kFineAlpha) levels = fineLevels;
  vec4 encoded;
  for (int k = 0; k < 4; ++k)
    encoded[k] = levels[k] < 0.0 ? 1.0 : encodeShellDepth(levels[k], frame.shell.yz);
  imageStore(opacityDepths, pixel, encoded);
  if (kEmission) imageStore(emission, pixel, vec4(fine.y));
}
