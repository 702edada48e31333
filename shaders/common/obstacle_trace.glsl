// Rays (t >= 0) against the scene's obstacles (src/render/obstacle_bvh.h, whose nearestHit() is the CPU mirror): each
// obstacle's bounding-volume hierarchy around its placement point, tried in turn where the ray meets the
// obstacle's world bounds. The including shader defines OBSTACLE_NODES_BINDING, OBSTACLE_TRIANGLES_BINDING and
// OBSTACLE_RECORDS_BINDING before including this file, and passes the obstacle count.
#ifndef SIXWAY_OBSTACLE_TRACE_GLSL
#define SIXWAY_OBSTACLE_TRACE_GLSL

#include "volume.glsl"  // rayBox, safeInverse

// BvhNode: (min, leftOrFirst), (max, count) — the ints as float bits.
layout(std430, binding = OBSTACLE_NODES_BINDING) readonly buffer ObstacleNodes { vec4 obstacleNodes[]; };
// BvhTriangle: p0, p1, p2, n0, n1, n2.
layout(std430, binding = OBSTACLE_TRIANGLES_BINDING) readonly buffer ObstacleTriangles {
  vec4 obstacleTriangles[];
};
// ObstacleRecord: (placement, root), (world min, casts shadows), (world max, -).
layout(std430, binding = OBSTACLE_RECORDS_BINDING) readonly buffer ObstacleRecords { vec4 obstacleRecords[]; };

const int kObstacleStack = 64;  // deeper than any hierarchy of a few million triangles

struct ObstacleHit {
  float t;
  vec3 normal;  // interpolated from the corners' normals, unit, not turned toward the ray
  int obstacle;
};

// Möller–Trumbore: (t, u, v), t = 3.4e38 when the ray misses triangle `tri`.
vec3 obstacleTriangleHit(int tri, vec3 o, vec3 w) {
  vec3 p0 = obstacleTriangles[6 * tri].xyz;
  vec3 e1 = obstacleTriangles[6 * tri + 1].xyz - p0, e2 = obstacleTriangles[6 * tri + 2].xyz - p0;
  vec3 p = cross(w, e2);
  float det = dot(e1, p);
  if (abs(det) < 1e-20) return vec3(3.4e38);
  float inv = 1.0 / det;
  vec3 s = o - p0;
  float u = dot(s, p) * inv;
  if (u < 0.0 || u > 1.0) return vec3(3.4e38);
  vec3 q = cross(s, e1);
  float v = dot(w, q) * inv;
  if (v < 0.0 || u + v > 1.0) return vec3(3.4e38);
  return vec3(dot(e2, q) * inv, u, v);
}

// The nearest hit with t in (tMin, tMax) of the obstacles (casters only: those that cast shadows), or false.
// With `anyHit`, the first hit found (a shadow ray: whether anything blocks, not what).
bool traceObstacles(vec3 o, vec3 w, float tMin, float tMax, int count, bool castersOnly, bool anyHit,
                    out ObstacleHit hit) {
  vec3 invW = safeInverse(w);
  float tBest = tMax;
  int bestTriangle = -1;
  vec2 bestUv = vec2(0.0);
  hit.obstacle = -1;
  uint stack[kObstacleStack];
  for (int k = 0; k < count; ++k) {
    vec4 placement = obstacleRecords[3 * k], lo = obstacleRecords[3 * k + 1], hi = obstacleRecords[3 * k + 2];
    if (castersOnly && lo.w == 0.0) continue;
    vec2 span = rayBox(o, invW, lo.xyz, hi.xyz);
    if (span.x > span.y || span.y <= tMin || span.x >= tBest) continue;
    vec3 local = o - placement.xyz;
    int depth = 0;
    stack[depth++] = uint(placement.w);
    while (depth > 0) {
      uint node = stack[--depth];
      vec4 a = obstacleNodes[2 * node], b = obstacleNodes[2 * node + 1];
      vec2 box = rayBox(local, invW, a.xyz, b.xyz);
      if (box.x > box.y || box.y <= tMin || box.x >= tBest) continue;
      uint first = floatBitsToUint(a.w), n = floatBitsToUint(b.w);
      if (n == 0u) {
        if (depth + 2 > kObstacleStack) continue;  // never with the hierarchies built here
        stack[depth++] = first;
        stack[depth++] = first + 1u;
        continue;
      }
      for (uint i = first; i < first + n; ++i) {
        vec3 t = obstacleTriangleHit(int(i), local, w);
        if (!(t.x > tMin && t.x < tBest)) continue;
        tBest = t.x;
        bestTriangle = int(i);
        bestUv = t.yz;
        hit.obstacle = k;
        if (anyHit) {
          hit.t = tBest;
          hit.normal = vec3(0.0);
          return true;
        }
      }
    }
  }
  if (bestTriangle < 0) return false;
  hit.t = tBest;
  hit.normal = normalize((1.0 - bestUv.x - bestUv.y) * obstacleTriangles[6 * bestTriangle + 3].xyz +
                         bestUv.x * obstacleTriangles[6 * bestTriangle + 4].xyz +
                         bestUv.y * obstacleTriangles[6 * bestTriangle + 5].xyz);
  return true;
}

#endif
