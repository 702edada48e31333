// Per-frame values of the lit obstacle pass (src/render/obstacle_pass.cpp mirrors this std140 block).
#ifndef SIXWAY_OBSTACLE_PARAMS_GLSL
#define SIXWAY_OBSTACLE_PARAMS_GLSL

#define OBSTACLE_MAX_LIGHTS 8

layout(std140, binding = 0) uniform ObstacleParams {
  mat4 viewProjection;  // render::projectionMatrix(frame, scene depth range) · viewMatrix(camera)
  vec4 eye;             // xyz: the camera position; w: the shadow atlas' tile size
  vec4 albedo;          // rgb: diffuse albedo; w: the number of lights
  vec4 ambient[4];      // rgb: L0, L1x, L1y, L1z of the ambient radiance, max(0, L0 + L1·w) from direction w
  // xyz: unit direction toward a directional light (w = 0), or a point light's position (w = 1)
  vec4 lightVector[OBSTACLE_MAX_LIGHTS];
  // rgb: colour · intensity (directional: the irradiance facing the light; point: irradiance · r²)
  vec4 lightIntensity[OBSTACLE_MAX_LIGHTS];
  // x: the light's tile of the shadow atlas (−1: no shadow map); y: the world size of a texel per unit of its
  // clip w (render::ShadowMaps)
  vec4 lightShadow[OBSTACLE_MAX_LIGHTS];
  mat4 lightViewProjection[OBSTACLE_MAX_LIGHTS];  // world → the light's clip space
}
params;

#endif
