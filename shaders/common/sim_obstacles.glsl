// Point-in-obstacle tests in lattice coordinates, for the analytic shapes and voxelized meshes.
#ifndef SIXWAY_SIM_OBSTACLES_GLSL
#define SIXWAY_SIM_OBSTACLES_GLSL

#include "sim_grid.glsl"

// `occupancy` is the caller's buffer of mesh inside/outside bits (one uint per object voxel).
bool insideObstacle(Obstacle o, vec3 p) {
  vec3 d = p - o.centre.xyz;
  uint shape = uint(o.centre.w);
  if (shape == SHAPE_SPHERE) return dot(d, d) <= o.size.x * o.size.x;
  if (shape == SHAPE_CYLINDER) {
    float along = dot(d, o.axis.xyz);
    vec3 across = d - along * o.axis.xyz;
    return abs(along) <= o.axis.w && dot(across, across) <= o.size.x * o.size.x;
  }
  if (shape == SHAPE_BOX) return all(lessThanEqual(abs(d), o.size.xyz));
  if (shape == SHAPE_CAPSULE) {  // within the radius of the segment along the axis
    vec3 across = d - clamp(dot(d, o.axis.xyz), -o.axis.w, o.axis.w) * o.axis.xyz;
    return dot(across, across) <= o.size.x * o.size.x;
  }
  // Mesh: into object space, then the occupancy voxel that holds the point.
  vec3 object = vec3(dot(o.rotation[0].xyz, d), dot(o.rotation[1].xyz, d), dot(o.rotation[2].xyz, d));
  ivec3 voxel = ivec3(floor((object - o.meshOrigin.xyz) / o.meshOrigin.w));
  if (any(lessThan(voxel, ivec3(0))) || any(greaterThanEqual(voxel, o.meshGrid.xyz))) return false;
  uint word = uint(o.meshGrid.w) + uint(voxel.x + o.meshGrid.x * (voxel.y + o.meshGrid.y * voxel.z));
  return meshOccupied(word);
}

#endif
