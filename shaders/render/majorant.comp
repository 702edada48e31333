#version 460
// The largest density a trilinear lookup can return inside each brick of BRICK³ cells: the maximum over
// the brick's cells and the one-cell ring around it (a point near a brick face interpolates the cells
// across it). Delta and ratio tracking (path_trace.comp) use it as a piecewise-constant majorant.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(std430, binding = 0) readonly buffer Density { float density[]; };
layout(std430, binding = 1) writeonly buffer Majorants { float brickMax[]; };
layout(push_constant) uniform Push {
  ivec4 size;    // xyz: cells
  ivec4 bricks;  // xyz: bricks per axis; w: cells per brick side
} push;

void main() {
  ivec3 b = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(b, push.bricks.xyz))) return;
  ivec3 lo = max(b * push.bricks.w - 1, ivec3(0));
  ivec3 hi = min(b * push.bricks.w + push.bricks.w, push.size.xyz - 1);
  float m = 0.0;
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x) m = max(m, density[(z * push.size.y + y) * push.size.x + x]);
  brickMax[(b.z * push.bricks.y + b.y) * push.bricks.x + b.x] = m;
}
