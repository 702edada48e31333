#pragma once
// CPU oracle of the six-way billboard shading (docs/conventions.md, "Shading"; docs/real-time-rendering.md,
// "Six-way shading"), in double precision and written from the documented formulas, pixel by pixel: the pixel
// centre's point of the image plane, the lightmaps there (Catmull-Rom cubic, clamp to edge), the shell point,
// the share of the smoke's opacity in front of the obstacle (or the obstacle test at the shell), Unity's
// remapping, each light with squared six-way weights and its PCF shadow, L1 ambient, the emissive gradient,
// premultiplied-over the background.
#include <array>
#include <optional>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "io/image.h"
#include "render/camera.h"
#include "render/projection.h"
#include "render/sixway_shading.h"
#include "scene/scene.h"

namespace sixway::test {

struct CpuShadingInputs {
  render::Camera camera;
  render::ImagePlane frame, billboard;
  render::DepthRange shellRange, sceneRange;
  std::vector<render::ShadingLight> lights;
  std::optional<scene::Ambient> ambient;
  render::ShadingControls controls;
  const io::Image* lightmapA = nullptr;      // RGBA
  const io::Image* lightmapB = nullptr;      // RGBA
  const io::Image* guide = nullptr;          // RGBA, B = encoded shell depth; none: no shell anywhere
  const io::Image* obstacleDepth = nullptr;  // one channel, depth-buffer values, the target's size
  const io::Image* opacityDepths = nullptr;  // RGBA, the guide's size, encoded as the shell; needs `guide`
  const io::Image* shadowAtlas = nullptr;    // one channel, tileSize wide, tiles stacked vertically
  int tileSize = 0;
  double pcfRadius = 1.5, depthBias = 0.002;
};

// The target (RGBA, premultiplied) after drawing the smoke over `background` (RGBA, the target's size).
io::Image cpuSixWayShading(const CpuShadingInputs& in, const io::Image& background);

// The lit fraction of `world` for the light whose shadow map is tile `tile` of the atlas: the mean over the
// box of half-width `radius` texels around the point of "the nearest texel cell under this point lets the
// (biased) depth through", cells of the tile's edge extending outwards; radius 0: the cell under the point.
double cpuShadowVisibility(const io::Image& atlas, int tileSize, int tile, const glm::mat4& shadowMatrix,
                           const glm::dvec3& world, double radius, double bias);

// The world point the shading uses at pixel (x, y): the shell point, else the billboard's plane.
glm::dvec3 cpuShadedPoint(const CpuShadingInputs& in, int width, int height, int x, int y);
// The view depth the shading gives the point at `uv` (0..1 across `guide`): bilinear over the four nearest
// texels, each the shell's depth (channel 2, encoded in [near, far]) or `planeDepth` where it has none
// (shaders/common/depth.glsl).
double cpuShadedViewDepth(const io::Image& guide, glm::dvec2 uv, double near, double far, double planeDepth);

// The view depths over which the shading averages a light's obstacle shadow at `uv`
// (docs/real-time-rendering.md, "Smoke and obstacles"): where the opacity reaches 0.1, 0.35 and 0.6, each
// bilinear over the four nearest texels of `levels` (the guide's opacity depths, encoded in [near, far]), a
// level a texel does not reach counting as the texel's last one reached, or as `planeDepth` where it reaches
// none.
std::array<double, 3> cpuShadowDepths(const io::Image& levels, glm::dvec2 uv, double near, double far,
                                      double planeDepth);

// The opacity of the smoke in front of view depth d along one guide texel's ray, whose opacity reaches
// `total` and the levels 0.1, 0.35, 0.6, 0.85 at `levels` (view depths, < 0: not reached), as
// docs/real-time-rendering.md, "Smoke and obstacles" states it: piecewise linear through the reached levels,
// ramping up from 0 before the first (over 0.4 of the depth between the first two) and on to `total` after
// the last at the slope of the interval before it; a ray reaching no level holds all of `total` at
// `thinDepth`; averaged over [d − w, d + w] (w > 0).
double cpuOpacityInFront(const std::array<double, 4>& levels, double total, double d, double thinDepth,
                         double w);

// The lit fraction of `world` averaged over a square `halfWidth` metres either side of it across the light's
// beam (4 × 4 taps at ±0.25 and ±0.75 of the half-width, the texel under each), or cpuShadowVisibility with
// `radius` where that square spans fewer texels.
double cpuWideShadowVisibility(const io::Image& atlas, int tileSize, int tile, const glm::mat4& shadowMatrix,
                               const glm::dvec3& world, double halfWidth, double radius, double bias);

}  // namespace sixway::test
