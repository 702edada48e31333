#version 460
// One tile of the shadow-map atlas (src/render/shadow_maps.h): the shadow-casting obstacles through the
// light's view-projection; depth 0 nearest the light, 1 at the far side of the scene bounds.
#extension GL_GOOGLE_include_directive : require
#define OBSTACLE_PLACEMENTS_BINDING 1
#include "obstacle_vertex.glsl"

layout(std430, binding = 0) readonly buffer Lights {
  mat4 lightViewProjection[];  // per tile
};
layout(push_constant) uniform Push {
  uint tile;
};

void main() { gl_Position = lightViewProjection[tile] * vec4(obstacleWorldPosition(), 1.0); }
