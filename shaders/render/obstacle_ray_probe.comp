#version 460
// Test of obstacle_trace.glsl (tests/realtime/test_obstacle_bvh.cpp): one ray per invocation against the
// obstacles, its nearest hit (or any hit) written out for comparison with render::ObstacleBvh::nearestHit.
#extension GL_GOOGLE_include_directive : require
#define OBSTACLE_NODES_BINDING 0
#define OBSTACLE_TRIANGLES_BINDING 1
#define OBSTACLE_RECORDS_BINDING 2
#include "obstacle_trace.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 3) readonly buffer Rays { vec4 rays[]; };  // (origin, tMin), (direction, tMax)
layout(std430, binding = 4) writeonly buffer Hits { vec4 hits[]; };  // (t, -1 for none), (normal, obstacle)
layout(push_constant) uniform Push {
  uint rays;       // count
  int obstacles;   // count
  uint castersOnly;
  uint anyHit;
} push;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.rays) return;
  vec4 o = rays[2 * i], w = rays[2 * i + 1];
  ObstacleHit hit;
  if (traceObstacles(o.xyz, w.xyz, o.w, w.w, push.obstacles, push.castersOnly != 0u, push.anyHit != 0u, hit)) {
    hits[2 * i] = vec4(hit.t, 0.0, 0.0, 0.0);
    hits[2 * i + 1] = vec4(hit.normal, float(hit.obstacle));
  } else {
    hits[2 * i] = vec4(-1.0, 0.0, 0.0, 0.0);
    hits[2 * i + 1] = vec4(0.0, 0.0, 0.0, -1.0);
  }
}
