// The obstacle meshes as the rasterized passes read them (src/render/obstacle_meshes.h): vertices around
// each obstacle's placement point, and the placement points of the current frame in a buffer.
#ifndef SIXWAY_OBSTACLE_VERTEX_GLSL
#define SIXWAY_OBSTACLE_VERTEX_GLSL

layout(location = 0) in vec3 inOffset;  // from the placement point, world axes
layout(location = 1) in uint inObstacle;
layout(location = 2) in vec3 inNormal;

layout(std430, binding = OBSTACLE_PLACEMENTS_BINDING) readonly buffer Placements {
  vec4 placements[];  // xyz: where each obstacle is this frame
};

vec3 obstacleWorldPosition() { return placements[inObstacle].xyz + inOffset; }

#endif
