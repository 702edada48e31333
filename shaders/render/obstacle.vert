#version 460
// The lit obstacle pass (src/render/obstacle_pass.h): obstacle meshes through the camera's view-projection.
#extension GL_GOOGLE_include_directive : require
#define OBSTACLE_PLACEMENTS_BINDING 1
#include "obstacle_params.glsl"
#include "obstacle_vertex.glsl"

layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldNormal;

void main() {
  worldPosition = obstacleWorldPosition();
  worldNormal = inNormal;
  gl_Position = params.viewProjection * vec4(worldPosition, 1.0);
}
