#version 460
// Volumetric path tracer (Monte Carlo, unbiased). Per pixel and sample: a camera ray; free paths by delta
// tracking (Woodcock et al. 1965) against the piecewise-constant brick majorants of majorant.comp; at
// each real collision the path weight is multiplied by the albedo, every light is sampled (next-event
// estimation) with its transmittance by ratio tracking (Novák et al. 2014, "Residual Ratio Tracking for
// Estimating Attenuation in Participating Media"), and the path continues in a direction drawn from the
// Henyey–Greenstein phase function, up to the given number of scattering orders. Emission is collected at
// every tentative collision as j / σ̄ (σ̄ the local majorant). A path that leaves the volume sees the
// background (camera rays) or the environment (scattered rays). alpha = 1 − T of the camera ray, by ratio
// tracking. Each pass adds its samples to the running sums in `accumulated`.
//
// Obstacles (image mode only; render::ObstacleBvh, obstacle_trace.glsl): opaque Lambertian surfaces of the
// real-time pass's albedo and triangles. A ray that reaches one before colliding in the smoke sees its surface:
// every light sampled there (the cosine, the obstacles that cast shadows, the smoke's transmittance), then the
// path goes on in a cosine-distributed direction (one more order), so that the environment, the smoke's
// scattered light and the other obstacles light it too. Shadow rays from the smoke stop at obstacles that cast
// shadows (and only for lights that cast them: PathLight.radiance.w). A camera ray that meets an obstacle is
// opaque (alpha 1).
//
// SIXWAY: six-way lightmaps: each light writes the channel it names; channel 6 is alpha and channel 7
// the luminance of the emission, seen directly and after scattering (no background, no environment).
// Otherwise: RGB radiance in channels 0–2 and alpha in channel 3.
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"
#include "emission.glsl"
#include "phase.glsl"
#include "random.glsl"
#include "volume.glsl"
#define OBSTACLE_NODES_BINDING 5
#define OBSTACLE_TRIANGLES_BINDING 6
#define OBSTACLE_RECORDS_BINDING 7
#include "obstacle_trace.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const bool SIXWAY = false;

const int kMaxLights = 8;

struct PathLight {
  vec4 position;  // xyz: direction toward the light (w = 0, directional) or its position (w = 1, point)
  // xyz: colour · irradiance (directional) or colour · intensity (point); w: six-way channel (SIXWAY), else 1
  // when obstacles cast shadows from this light
  vec4 radiance;
};

layout(std140, binding = 0) uniform TraceParams {
  VolumeGrid volume;
  CameraRays camera;
  vec4 optics;   // x: extinction per unit density, y: albedo, z: HG g, w: emission intensity
  ivec4 bricks;  // xyz: majorant bricks per axis; w: cells per brick side
  uvec4 frame;   // x: seed; y: index of this pass's first sample; z: samples per pixel in this pass; w: max orders
  ivec4 image;   // xy: image size; z: emission ramp keys (0: no emission); w: lights
  uvec4 flags;   // x: jitter inside pixels; y: temperature grid present; z: lowest scattering order recorded
  vec4 background;      // rgb: radiance seen by camera rays that leave the volume
  vec4 obstacles;       // x: count (0: none; always 0 in SIXWAY mode); y: their albedo; z: surface offset (m)
  vec4 environment[4];  // rgb: L0, L1x, L1y, L1z; radiance arriving from direction w: max(0, L0 + L1·w)
  vec4 ramp[kMaxRampKeys];
  PathLight lights[kMaxLights];
}
params;

#define RAMP_KEYS params.ramp
#include "emission_ramp.glsl"

layout(std430, binding = 1) readonly buffer Density { float density[]; };
layout(std430, binding = 2) readonly buffer Temperature { float temperature[]; };
layout(std430, binding = 3) readonly buffer Majorants { float brickMax[]; };
layout(std430, binding = 4) buffer Accumulation { float accumulated[]; };  // channel-planar sums

vec3 boxMin, boxMax;

// The majorant σ̄ of the brick that the ray o + t·w enters just after t, and the distance to its far side.
float brickSegment(vec3 o, vec3 w, vec3 invW, float t, out float sigmaBar) {
  float brickSize = float(params.bricks.w) * params.volume.originCell.w;
  float nudge = 1e-4 * brickSize;
  vec3 p = o + (t + nudge) * w;
  ivec3 b = clamp(ivec3(floor((p - boxMin) / brickSize)), ivec3(0), params.bricks.xyz - 1);
  vec3 lo = boxMin + vec3(b) * brickSize;
  vec3 far = max((lo - o) * invW, (lo + brickSize - o) * invW);
  sigmaBar = params.optics.x * brickMax[(b.z * params.bricks.y + b.y) * params.bricks.x + b.x];
  return max(min(far.x, min(far.y, far.z)), t + nudge);
}

// Delta tracking from t to the first real collision before tEnd (true, t at the collision) or to tEnd
// (false). With `emitting`, adds the emission estimate j / σ̄ at every tentative collision.
bool deltaTrack(vec3 o, vec3 w, float tEnd, inout float t, inout uint rng, bool emitting, inout vec3 emitted) {
  vec3 invW = safeInverse(w);
  while (t < tEnd) {
    float sigmaBar;
    float segmentEnd = min(brickSegment(o, w, invW, t, sigmaBar), tEnd);
    if (sigmaBar <= 0.0) {
      t = segmentEnd;
      continue;
    }
    t -= log(1.0 - rngNext(rng)) / sigmaBar;
    if (t >= segmentEnd) {  // no collision in this brick: start afresh at its face (memoryless)
      t = segmentEnd;
      continue;
    }
    Lerp8 l = lerp8(params.volume.size.xyz, volumeSampleCoord(params.volume, o + t * w));
    float rho = max(0.0, LERP8(density, l));
    if (emitting && rho > 0.0) {
      float temp = params.flags.y != 0u ? LERP8(temperature, l) : 0.0;
      emitted += params.optics.w * rho * rampColor(params.image.z, temp) / sigmaBar;
    }
    if (rngNext(rng) * sigmaBar < params.optics.x * rho) return true;
  }
  return false;
}

// Transmittance along o + t·w for t in [t, tEnd] by ratio tracking, with Russian roulette once it is small.
float ratioTrack(vec3 o, vec3 w, float t, float tEnd, inout uint rng) {
  vec3 invW = safeInverse(w);
  float T = 1.0;
  while (t < tEnd) {
    float sigmaBar;
    float segmentEnd = min(brickSegment(o, w, invW, t, sigmaBar), tEnd);
    if (sigmaBar <= 0.0) {
      t = segmentEnd;
      continue;
    }
    t -= log(1.0 - rngNext(rng)) / sigmaBar;
    if (t >= segmentEnd) {
      t = segmentEnd;
      continue;
    }
    Lerp8 l = lerp8(params.volume.size.xyz, volumeSampleCoord(params.volume, o + t * w));
    T *= max(0.0, 1.0 - params.optics.x * max(0.0, LERP8(density, l)) / sigmaBar);
    if (T < 0.1) {
      if (rngNext(rng) >= 0.5) return 0.0;
      T *= 2.0;
    }
  }
  return T;
}

vec3 environmentRadiance(vec3 w) {
  vec3 l = params.environment[0].rgb + w.x * params.environment[1].rgb + w.y * params.environment[2].rgb +
           w.z * params.environment[3].rgb;
  return max(l, vec3(0.0));
}

int obstacleCount() {
  return SIXWAY ? 0 : int(params.obstacles.x);
}

// The nearest obstacle along o + t·w (t in (tMin, tMax)), or t = 3.4e38.
ObstacleHit nearestObstacle(vec3 o, vec3 w, float tMin) {
  ObstacleHit hit;
  if (!traceObstacles(o, w, tMin, 3.4e38, obstacleCount(), false, false, hit)) hit.t = 3.4e38;
  return hit;
}

// Light i as seen from point o (unit direction, distance, falloff); false where an obstacle that casts shadows
// lies between (for lights that cast them).
bool lightSample(int i, vec3 o, float tMin, out vec3 toLight, out float tLight, out float falloff) {
  PathLight light = params.lights[i];
  toLight = light.position.xyz;
  falloff = 1.0;
  tLight = 3.4e38;
  if (light.position.w != 0.0) {
    vec3 d = light.position.xyz - o;
    tLight = length(d);
    toLight = d / tLight;
    falloff = 1.0 / (tLight * tLight);
  }
  ObstacleHit blocker;
  return obstacleCount() == 0 || light.radiance.w == 0.0 ||
         !traceObstacles(o, toLight, tMin, tLight, obstacleCount(), true, true, blocker);
}

// The smoke's transmittance from o toward a light, up to the light or out of the volume.
float transmittanceToLight(vec3 o, vec3 toLight, float tLight, inout uint rng) {
  vec2 span = rayBox(o, safeInverse(toLight), boxMin, boxMax);
  span.y = min(span.y, tLight);
  return span.x < span.y ? ratioTrack(o, toLight, span.x, span.y, rng) : 1.0;
}

// A direction about unit n with density cos θ / π (Malley's method: a uniform disc lifted to the hemisphere).
vec3 cosineSample(vec3 n, vec2 xi) {
  float r = sqrt(xi.x), phi = 6.28318530718 * xi.y;
  vec3 t = normalize(cross(abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0), n));
  vec3 b = cross(n, t);
  return normalize(r * cos(phi) * t + r * sin(phi) * b + sqrt(max(0.0, 1.0 - xi.x)) * n);
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = params.image.xy;
  if (any(greaterThanEqual(pixel, size))) return;
  boxMin = volumeBoxMin(params.volume);
  boxMax = volumeBoxMax(params.volume);
  const uint pixelIndex = uint(pixel.y * size.x + pixel.x);
  const float albedo = params.optics.y, g = params.optics.z;
  const float surfaceAlbedo = params.obstacles.y, surfaceOffset = params.obstacles.z;
  const bool hasEmission = params.image.z > 0;

  float sums[8] = float[8](0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
  for (uint s = 0u; s < params.frame.z; ++s) {
    uint rng = rngSeed(params.frame.x, pixelIndex, params.frame.y + s);
    vec2 offset = params.flags.x != 0u ? vec2(rngNext(rng), rngNext(rng)) : vec2(0.5);
    vec3 o = params.camera.position.xyz;
    vec3 w = cameraRayDirection(params.camera, vec2(pixel) + offset, vec2(size));
    // The smoke along the ray is [span.x, span.y), cut short by the nearest obstacle.
    vec2 span = rayBox(o, safeInverse(w), boxMin, boxMax);
    ObstacleHit surface = nearestObstacle(o, w, 0.0);
    span.y = min(span.y, surface.t);
    float viewTransmittance = span.x < span.y ? ratioTrack(o, w, span.x, span.y, rng) : 1.0;
    sums[SIXWAY ? 6 : 3] += surface.t < 3.4e38 ? 1.0 : 1.0 - viewTransmittance;

    vec3 radiance = vec3(0.0);  // RGB mode only
    float weight = 1.0;         // path throughput: the albedos of the collisions and surfaces so far
    for (uint order = 0u;; ++order) {
      // Emission seen after `order` scatterings; with flags.z = 2 (the orders the exact baker lacks) only the
      // scattered part, order >= 1.
      bool emitting = hasEmission && order + 1u >= params.flags.z;
      vec3 emitted = vec3(0.0);
      float t = span.x;
      bool collided = span.x < span.y && deltaTrack(o, w, span.y, t, rng, emitting, emitted);
      if (SIXWAY) {
        sums[7] += weight * luminance(emitted);
      } else {
        radiance += weight * emitted;
      }
      // Next-event estimation at the collision or surface is scattering order `order + 1`; orders below flags.z
      // are not recorded (flags.z = 2: multiple scattering only, the part the exact single-scattering baker lacks).
      const int recordedLights = order + 1u >= params.flags.z ? params.image.w : 0;
      if (!collided && surface.t < 3.4e38) {  // an obstacle: Lambertian, lit from the side the ray came from
        if (order == params.frame.w) break;  // its light would be one order more than the limit
        o += surface.t * w;
        vec3 n = dot(surface.normal, w) < 0.0 ? surface.normal : -surface.normal;
        o += surfaceOffset * n;
        for (int i = 0; i < recordedLights; ++i) {
          vec3 toLight;
          float tLight, falloff;
          float cosine = 0.0;
          if (lightSample(i, o, 0.0, toLight, tLight, falloff)) cosine = dot(n, toLight);
          if (cosine <= 0.0) continue;
          float lit = weight * falloff * (surfaceAlbedo / kPi) * cosine * transmittanceToLight(o, toLight, tLight, rng);
          radiance += lit * params.lights[i].radiance.rgb;
        }
        weight *= surfaceAlbedo;  // the cosine-distributed bounce: BRDF · cos / pdf = albedo
        w = cosineSample(n, vec2(rngNext(rng), rngNext(rng)));
        span = rayBox(o, safeInverse(w), boxMin, boxMax);
        surface = nearestObstacle(o, w, 0.0);
        span.y = min(span.y, surface.t);
        continue;
      }
      if (!collided) {
        if (!SIXWAY) radiance += weight * (order == 0u ? params.background.rgb : environmentRadiance(w));
        break;
      }
      if (order == params.frame.w) break;  // a further scattering would exceed the order limit
      weight *= albedo;
      o += t * w;
      for (int i = 0; i < recordedLights; ++i) {
        vec3 toLight;
        float tLight, falloff;
        if (!lightSample(i, o, 0.0, toLight, tLight, falloff)) continue;
        float tExit = min(rayBox(o, safeInverse(toLight), boxMin, boxMax).y, tLight);
        float lit = weight * falloff * hgPhase(dot(toLight, w), g) * ratioTrack(o, toLight, 0.0, tExit, rng);
        if (SIXWAY) {
          sums[int(params.lights[i].radiance.w)] += lit * params.lights[i].radiance.x;
        } else {
          radiance += lit * params.lights[i].radiance.rgb;
        }
      }
      w = hgSample(w, g, vec2(rngNext(rng), rngNext(rng)));
      span = vec2(0.0, rayBox(o, safeInverse(w), boxMin, boxMax).y);
      surface = nearestObstacle(o, w, 0.0);
      span.y = min(span.y, surface.t);
    }
    if (!SIXWAY) {
      sums[0] += radiance.r;
      sums[1] += radiance.g;
      sums[2] += radiance.b;
    }
  }
  const uint channels = SIXWAY ? 8u : 4u, plane = uint(size.x * size.y);
  for (uint c = 0u; c < channels; ++c) accumulated[c * plane + pixelIndex] += sums[c];
}
