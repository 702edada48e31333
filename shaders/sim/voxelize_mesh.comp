#version 460
// Voxelizes a triangle mesh by ray parity: for each triangle and axis, every row of voxel centres
// along that axis that pierces the triangle toggles the parity bit of all voxels beyond the hit.
// Bits 0, 1, 2 hold the parity along x, y, z; a voxel is inside where at least two agree, which
// tolerates the small holes of scanned meshes (the Stanford bunny's base) that break single-axis parity.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Positions { float positions[]; };  // xyz per vertex
layout(std430, binding = 1) readonly buffer Triangles { uint triangles[]; };   // 3 vertex indices each
layout(std430, binding = 2) buffer Occupancy { uint occupancy[]; };
layout(push_constant) uniform Push {
  vec4 origin;   // xyz: object-space corner of the grid; w: voxel size
  ivec4 grid;    // xyz: voxels; w: first word of this mesh in the occupancy buffer
  uint triangleCount;
} push;

vec3 vertex(uint i) { return vec3(positions[3u * i], positions[3u * i + 1u], positions[3u * i + 2u]); }

// 2D edge function, with ties broken so that a point on a shared edge counts for exactly one of
// the two triangles (a top-left style rule), keeping the parity watertight.
bool edgeInside(vec2 a, vec2 b, vec2 p) {
  float e = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
  if (e != 0.0) return e > 0.0;
  return (b.y > a.y) || (b.y == a.y && b.x < a.x);
}

void main() {
  uint id = gl_GlobalInvocationID.x;
  if (id >= 3u * push.triangleCount) return;
  int axis = int(id % 3u);
  uint t = id / 3u;
  int u = (axis + 1) % 3, v = (axis + 2) % 3;  // the plane the rows are laid out in
  vec3 p0 = (vertex(triangles[3u * t]) - push.origin.xyz) / push.origin.w;
  vec3 p1 = (vertex(triangles[3u * t + 1u]) - push.origin.xyz) / push.origin.w;
  vec3 p2 = (vertex(triangles[3u * t + 2u]) - push.origin.xyz) / push.origin.w;
  vec2 a = vec2(p0[u], p0[v]), b = vec2(p1[u], p1[v]), c = vec2(p2[u], p2[v]);
  float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  if (area == 0.0) return;  // edge-on: no row pierces it
  if (area < 0.0) {         // orient counter-clockwise in the plane
    vec2 s = b;
    b = c;
    c = s;
  }
  ivec2 lo = max(ivec2(ceil(min(a, min(b, c)) - 0.5)), ivec2(0));
  ivec2 hi = min(ivec2(floor(max(a, max(b, c)) - 0.5)), ivec2(push.grid[u], push.grid[v]) - 1);
  vec3 normal = cross(p1 - p0, p2 - p0);
  for (int j = lo.y; j <= hi.y; ++j)
    for (int i = lo.x; i <= hi.x; ++i) {
      vec2 p = vec2(i, j) + 0.5;  // voxel centres
      if (!edgeInside(a, b, p) || !edgeInside(b, c, p) || !edgeInside(c, a, p)) continue;
      // Where the row through p meets the triangle's plane n·(x − p0) = 0.
      float hit = p0[axis] - (normal[u] * (p.x - p0[u]) + normal[v] * (p.y - p0[v])) / normal[axis];
      int first = max(int(ceil(hit - 0.5)), 0);
      for (int k = first; k < push.grid[axis]; ++k) {
        ivec3 voxel;
        voxel[axis] = k;
        voxel[u] = i;
        voxel[v] = j;
        uint word = uint(push.grid.w) + uint(voxel.x + push.grid.x * (voxel.y + push.grid.y * voxel.z));
        atomicXor(occupancy[word], 1u << uint(axis));
      }
    }
}
