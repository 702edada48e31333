#version 460
// Optical depth toward one light at every node of its light grid: one invocation per column, which
// marches away from the light and accumulates ∫ σ_t ds node after node. Each interval between nodes is
// clipped to the volume's box and integrated with equal midpoint steps no longer than the step limit,
// so a constant density gives the exact optical depth. Samples in empty bricks (majorant.comp) are not
// looked up: their density is exactly zero.
#extension GL_GOOGLE_include_directive : require
#include "bake_params.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 1) readonly buffer Density { float density[]; };
layout(std430, binding = 2) readonly buffer Majorants { float brickMax[]; };
layout(std430, binding = 3) writeonly buffer Depth { float depth[]; };
layout(push_constant) uniform Push { uint light; } push;

void main() {
  LightGrid g = params.lights[push.light];
  ivec2 column = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(column, g.nodes.xy))) return;
  vec3 start = g.corner.xyz + float(column.x) * g.corner.w * g.u.xyz + float(column.y) * g.corner.w * g.v.xyz;
  vec3 away = -g.toLight.xyz;
  float interval = g.u.w, maxStep = g.v.w;
  vec3 boxMin = volumeBoxMin(params.volume);
  vec2 inside = rayBox(start, safeInverse(away), boxMin, volumeBoxMax(params.volume));
  const float brickSize = float(params.bricks.w) * params.volume.originCell.w;
  uint stride = uint(g.nodes.x * g.nodes.y);
  uint index = uint(column.y * g.nodes.x + column.x);

  float tau = 0.0;
  depth[index] = 0.0;
  for (int c = 1; c < g.nodes.z; ++c) {
    float t0 = max(float(c - 1) * interval, inside.x), t1 = min(float(c) * interval, inside.y);
    if (t1 > t0) {
      int steps = int(ceil((t1 - t0) / maxStep));
      float h = (t1 - t0) / float(steps);
      for (int s = 0; s < steps; ++s) {
        vec3 p = start + (t0 + (float(s) + 0.5) * h) * away;
        ivec3 b = clamp(ivec3(floor((p - boxMin) / brickSize)), ivec3(0), params.bricks.xyz - 1);
        if (brickMax[(b.z * params.bricks.y + b.y) * params.bricks.x + b.x] <= 0.0) continue;
        Lerp8 l = lerp8(params.volume.size.xyz, volumeSampleCoord(params.volume, p));
        tau += h * params.optics.x * max(0.0, LERP8(density, l));
      }
    }
    depth[index + uint(c) * stride] = tau;
  }
}
