#pragma once
// Host mirrors of the parameter blocks of the render shaders: every member is 16 bytes wide, so the C++ and
// GLSL layouts (std140 and std430 alike) agree member for member (checked by the static_asserts).
// lavapipe (Mesa 22) specializes a shader on the uniform-block values its branches and loop bounds test and
// compiles it again, about 0.5 s on the 2-core machine, whenever they change. So the blocks whose values
// change every frame (the six-way shading's, the guide march's, the motion field's: the camera) are read-only
// storage buffers, which it does not specialize on, and so is the baker's view march's (it kept a compiled
// copy per dispatch: shaders/render/bake_params.glsl); the baker's light depths and the path tracer's, fixed
// per setting, stay uniform blocks, on which the specialization makes them faster (docs/benchmarks.md,
// "Shaders compiled again every frame").
#include <glm/vec4.hpp>

#include "render/camera.h"
#include "render/light_grid.h"
#include "render/volume.h"
#include "scene/scene.h"

namespace sixway::render::layout {

constexpr int kMaxRampKeys = 16;  // shaders/common/emission.glsl
constexpr int kMaxLights = 8;     // shaders/render/path_trace.comp

struct VolumeGrid {  // shaders/common/volume.glsl
  glm::vec4 originCell;
  glm::ivec4 size;
};

struct CameraRays {  // shaders/common/camera.glsl
  glm::vec4 position, right, up, forward, plane;
};

struct LightGrid {  // shaders/render/bake_params.glsl
  glm::vec4 corner, u, v, toLight;
  glm::ivec4 nodes;
};

struct BakeParams {  // shaders/render/bake_params.glsl
  VolumeGrid volume;
  CameraRays camera;
  glm::vec4 optics;
  glm::vec4 march;
  glm::ivec4 image;
  glm::ivec4 bricks;
  glm::vec4 ramp[kMaxRampKeys];
  LightGrid lights[6];
};
static_assert(sizeof(BakeParams) == 16 * (2 + 5 + 4 + kMaxRampKeys + 6 * 5));

struct PathLight {  // shaders/render/path_trace.comp
  glm::vec4 position, radiance;
};

struct TraceParams {  // shaders/render/path_trace.comp
  VolumeGrid volume;
  CameraRays camera;
  glm::vec4 optics;
  glm::ivec4 bricks;
  glm::uvec4 frame;
  glm::ivec4 image;
  glm::uvec4 flags;
  glm::vec4 background;
  glm::vec4 obstacles;
  glm::vec4 environment[4];
  glm::vec4 ramp[kMaxRampKeys];
  PathLight lights[kMaxLights];
};
static_assert(sizeof(TraceParams) == 16 * (2 + 5 + 7 + 4 + kMaxRampKeys + 2 * kMaxLights));

VolumeGrid volumeGrid(const render::VolumeGrid& grid);
CameraRays cameraRays(const Camera& camera, const ImagePlane& plane);
LightGrid lightGrid(const render::LightGrid& grid);
// The emission ramp as (temperature, r, g, b) keys; returns the key count, 0 when the smoke does not emit.
// Throws io::InputError for more keys than the shaders hold.
int emissionRamp(const scene::Emission& emission, glm::vec4 (&keys)[kMaxRampKeys]);

}  // namespace sixway::render::layout
