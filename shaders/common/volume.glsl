// A dense, cell-centred scalar grid in a storage buffer (src/render/volume.h): cell (i, j, k) has its
// centre at origin + (i + 0.5, j + 0.5, k + 0.5) * cellSize, values x fastest, then y, then z.
// Sampling is trilinear, clamped to the edge inside the grid's box and zero outside it.
#ifndef SIXWAY_VOLUME_GLSL
#define SIXWAY_VOLUME_GLSL

struct VolumeGrid {
  vec4 originCell;  // xyz: world position of the corner of cell (0,0,0); w: cell size
  ivec4 size;       // xyz: cells per axis
};

// The eight samples around a continuous sample coordinate and the weights between them, as a base
// index plus the strides to the +x, +y, +z neighbours (0 where the edge clamps).
struct Lerp8 {
  uint base;
  uint dx, dy, dz;
  vec3 f;
};

// `g` is in sample units: g = (1, 2, 3) lies exactly on sample (1, 2, 3). Clamped to the edge.
Lerp8 lerp8(ivec3 size, vec3 g) {
  vec3 c = clamp(g, vec3(0.0), vec3(size - 1));
  ivec3 i0 = min(ivec3(c), size - 1);  // c >= 0, so the conversion is floor
  ivec3 step = min(i0 + 1, size - 1) - i0;
  Lerp8 l;
  l.base = uint((i0.z * size.y + i0.y) * size.x + i0.x);
  l.dx = uint(step.x);
  l.dy = uint(step.y * size.x);
  l.dz = uint(step.z * size.x * size.y);
  l.f = c - vec3(i0);
  return l;
}

// Trilinear interpolation of the float array `v` (any buffer member) at the Lerp8 `l`.
#define LERP8(v, l)                                                                                       \
  mix(mix(mix(v[l.base], v[l.base + l.dx], l.f.x), mix(v[l.base + l.dy], v[l.base + l.dy + l.dx], l.f.x), \
          l.f.y),                                                                                         \
      mix(mix(v[l.base + l.dz], v[l.base + l.dz + l.dx], l.f.x),                                           \
          mix(v[l.base + l.dz + l.dy], v[l.base + l.dz + l.dy + l.dx], l.f.x), l.f.y),                    \
      l.f.z)

vec3 volumeBoxMin(VolumeGrid grid) {
  return grid.originCell.xyz;
}
vec3 volumeBoxMax(VolumeGrid grid) {
  return grid.originCell.xyz + vec3(grid.size.xyz) * grid.originCell.w;
}
bool insideVolume(VolumeGrid grid, vec3 p) {
  return all(greaterThanEqual(p, volumeBoxMin(grid))) && all(lessThanEqual(p, volumeBoxMax(grid)));
}
// Sample coordinate of world point p: cell centres lie on integers.
vec3 volumeSampleCoord(VolumeGrid grid, vec3 p) {
  return (p - grid.originCell.xyz) / grid.originCell.w - 0.5;
}

// 1/d with zero components replaced by a huge value of the right sign, so slab tests never divide by zero.
vec3 safeInverse(vec3 d) {
  const float tiny = 1e-20;
  return 1.0 / mix(d, mix(vec3(-tiny), vec3(tiny), greaterThanEqual(d, vec3(0.0))), lessThan(abs(d), vec3(tiny)));
}

// Entry and exit distances of the ray o + t·d (t >= 0) through the box [lo, hi]; empty when x >= y.
vec2 rayBox(vec3 o, vec3 invD, vec3 lo, vec3 hi) {
  vec3 t0 = (lo - o) * invD, t1 = (hi - o) * invD;
  vec3 tNear = min(t0, t1), tFar = max(t0, t1);
  return vec2(max(max(tNear.x, tNear.y), max(tNear.z, 0.0)), min(min(tFar.x, tFar.y), tFar.z));
}

#endif
