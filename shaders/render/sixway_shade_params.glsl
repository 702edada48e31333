// Parameters of the six-way billboard shading (src/render/sixway_shading.cpp mirrors them), shared by
// billboard.vert and sixway_shade.frag. Per-frame values live in the parameter and light buffers, so a
// recorded frame replays; what fixes the recording (the shadow atlas, the obstacle depth image) is pushed.
#ifndef SIXWAY_SHADE_PARAMS_GLSL
#define SIXWAY_SHADE_PARAMS_GLSL

#include "camera.glsl"
#include "sixway_lighting.glsl"

layout(std430, binding = 0) readonly buffer ShadeParams {
  CameraRays camera;      // plane: the whole frame, i.e. the colour target
  vec4 frameToBillboard;  // the lightmaps' uv of frame uv f (both row 0 at the top): f · xy + zw
  vec4 depths;          // xy: view-depth range of the shell depth (the volume box); zw: the obstacle
                        // depth buffer's render::DepthMapping (offset rounded to float, scale)
  vec4 clipCorners[4];  // the billboard quad in clip space: bottom-left, bottom-right, top-right, top-left
  vec4 color;           // rgb: tint or absorption colour; w: absorption range r (Unity's units, 1/π .. 1)
  vec4 lightmapRemap;   // (inMin, inMax, outMin, outMax) for the six light channels
  vec4 alphaRemap;      // (inMin, inMax, outMin, outMax) for alpha
  vec4 misc;            // x: view depth of the billboard (the shaded point where there is no shell);
                        // y: emissive multiplier; z: emissive straight scale (0: Unity's gradient);
                        // w: the rest of the depth map's offset (offset − depths.z), depth.glsl
  ivec4 counts;         // x: lights; y: emissive gradient keys; z: flags (1 absorption, 2 lightmap remap,
                        // 4 alpha remap)
  vec4 ambient[4];      // rgb: L0, then L1 along the six-way x, y, z; radiance L(w) = L0 + L1·w; zero: none
  vec4 gradient[kMaxGradientKeys];  // emissive gradient keys (position, r, g, b)
}
params;

struct ShadeLight {
  vec4 vector;    // xyz: unit direction toward the light (w = 0, directional) or its position (w = 1, point)
  vec4 radiance;  // rgb: colour · intensity (irradiance, or radiant intensity of a point); w: shadow tile or
                  // −1
  mat4 shadowMatrix;  // world → the light's clip space (its shadow map)
};

layout(std430, binding = 1) readonly buffer ShadeLights {
  ShadeLight lights[];
};

layout(push_constant) uniform ShadePush {
  ivec4 frame;     // z: 1 with an obstacle depth image; w: 1 with opacity depths (xy unused)
  ivec4 atlas;     // x: shadow tile size in texels (0: no shadow atlas); y: tiles
  vec4 shadow;     // x: PCF radius in texels; y: depth bias (depth-buffer units)
  ivec4 viewport;  // the pixels of the colour target the camera's image covers: xy offset, zw extent
}
push;

#endif
