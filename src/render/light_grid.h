#pragma once
// The light-space lattice on which the reference baker stores optical depth toward a directional light.
// One axis runs along the light, so every column of nodes is one ray toward the light: a column is
// integrated once, front to back, instead of marching from every voxel separately, and the result is
// the same quadrature (see docs/reference-rendering.md). The GPU side is shaders/render/bake_params.glsl.
#include <cstdint>
#include <functional>
#include <glm/vec3.hpp>
#include <memory>

#include "render/volume.h"

namespace sixway::gpu {
class Context;
class Pipeline;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::render {

// Node (a, b, c) lies at corner + a·spacing·u + b·spacing·v − c·interval·toLight; c = 0 is the plane of
// the box corner nearest the light, where the optical depth is 0. u, v, toLight are orthonormal.
struct LightGrid {
  glm::vec3 corner{0.0f};
  glm::vec3 u{1, 0, 0}, v{0, 1, 0}, toLight{0, 0, 1};
  float spacing = 1.0f;   // between columns, across the light
  float interval = 1.0f;  // between nodes of a column, along the light
  float maxStep = 0.5f;   // quadrature step limit along a column
  glm::ivec3 nodes{0};    // along u, v, and away from the light

  uint64_t nodeCount() const { return uint64_t(nodes.x) * uint64_t(nodes.y) * uint64_t(nodes.z); }
  glm::vec3 node(int a, int b, int c) const {
    return corner + float(a) * spacing * u + float(b) * spacing * v - float(c) * interval * toLight;
  }
};

// The most nodes a light grid has along one axis: far more than a 2048-cell lattice's diagonal at a tenth of
// a cell, few enough that a grid's node count (and bytes) fits 64 bits.
inline constexpr int kMaxLightGridAxisNodes = 1 << 20;

// `nodes`, a count of nodes along one axis computed in floats, as an int. A box beyond a float's range (its
// size or diagonal inf) or a spacing of nothing give a count that is not finite or beyond
// kMaxLightGridAxisNodes: std::invalid_argument, rather than a wrapped int that no widening can shrink.
int lightGridAxisNodes(float nodes);

// The first spacing of `spacing`, 1.25·spacing, 1.25²·spacing, ... at which `fits` holds. Throws
// std::invalid_argument when `spacing` is not a finite positive number or nothing fits before the grids are a
// few nodes a side (by then any device holds them: a fit that never comes is a bug, not a long wait).
float widenedSpacing(float spacing, const std::function<bool(float)>& fits);

// The grid that covers the volume's box with columns `spacing` apart and nodes `spacing` apart along the
// light, shifted so that the projection of a cell centre falls on a node: along an axis of the volume, the
// optical depth is piecewise smooth between cell centres, and nodes on its kinks interpolate it far better.
// Throws std::invalid_argument for a box or spacing that gives no finite grid (lightGridAxisNodes).
LightGrid lightGridFor(const VolumeGrid& volume, glm::vec3 toLight, glm::vec3 u, glm::vec3 v, float spacing,
                       float maxStep);

// The pass that integrates the optical depth along the columns of a light grid (shaders/render/
// light_depth.comp; bindings: bake parameters, density, brick majorants, depths; push: the light's index).
std::unique_ptr<gpu::Pipeline> lightDepthPipeline(const gpu::Context& context,
                                                  const gpu::PipelineCache& cache);

}  // namespace sixway::render
