// Parameters of the reference six-way baker (src/reference/lightmap_baker.cpp mirrors them in
// src/render/gpu_layout.h), shared by light_depth.comp, sixway_march.comp and guide_march.comp.
#ifndef SIXWAY_BAKE_PARAMS_GLSL
#define SIXWAY_BAKE_PARAMS_GLSL

#include "camera.glsl"
#include "emission.glsl"
#include "volume.glsl"

// Optical depth toward one directional light on a light-space lattice (src/render/light_grid.h):
// node (a, b, c) at corner + a·spacing·u + b·spacing·v − c·interval·toLight, index (c·ny + b)·nx + a.
struct LightGrid {
  vec4 corner;   // xyz: node (0, 0, 0), on the light's side of the volume; w: spacing across the light
  vec4 u;        // xyz: first axis across the light; w: interval between nodes along the light
  vec4 v;        // xyz: second axis across the light; w: quadrature step limit along a column
  vec4 toLight;  // xyz: unit direction toward the light
  ivec4 nodes;   // xyz: nodes along u, along v, and away from the light
};

// A read-only storage buffer for the marches, which define BAKE_PARAMS_IN_STORAGE (the guide's and the baker's
// view march): lavapipe specializes a shader on the uniform-block values its branches test and, for the view
// march in a process that runs other passes between bakes, compiled a fresh copy at every dispatch and kept it
// until the pipeline was destroyed (550 KB of host memory per bake; `cli.long_run_reference`); the guide's
// camera changes every frame anyway (render/gpu_layout.h). light_depth.comp keeps the uniform block: the values
// it reads (lights[]) are indexed by a push constant, so they are not specialized on. The layouts agree: every
// member is 16 bytes wide.
#ifdef BAKE_PARAMS_IN_STORAGE
layout(std430, binding = 0) readonly buffer BakeParams {
#else
layout(std140, binding = 0) uniform BakeParams {
#endif
  VolumeGrid volume;
  CameraRays camera;
  vec4 optics;  // x: extinction per unit density, y: albedo, z: HG g, w: emission intensity
  vec4 march;   // x: view-ray step limit (world units), y: transmittance below which a view ray stops
  ivec4 image;  // xy: lightmap size; z: emission ramp keys (0: no emission); w: 1 with a temperature grid
  ivec4 bricks;  // xyz: empty-space bricks per axis (majorant.comp); w: cells per brick side
  vec4 ramp[kMaxRampKeys];  // (temperature, r, g, b)
  LightGrid lights[6];
}
params;

#define RAMP_KEYS params.ramp
#include "emission_ramp.glsl"

// Continuous node coordinate of world point p in a light grid (nodes on integers).
vec3 lightGridCoord(LightGrid g, vec3 p) {
  vec3 r = p - g.corner.xyz;
  return vec3(dot(r, g.u.xyz) / g.corner.w, dot(r, g.v.xyz) / g.corner.w, -dot(r, g.toLight.xyz) / g.u.w);
}

#endif
