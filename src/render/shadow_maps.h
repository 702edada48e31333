#pragma once
// Shadow maps of the obstacles (docs/conventions.md, "The frame"): one depth pass of the shadow-casting
// obstacle meshes from each shadow-casting light, into one D32 atlas of square tiles stacked vertically (tile
// t: rows t·S .. t·S + S−1). Each light's projection is fitted to the casters: across the beam it just holds
// the shadow-casting obstacles' bounds (plus a border wider than any filter), in depth it runs from their
// nearest corner to the far side of the scene bounds. Whatever projects outside the tile, or nearer than
// depth 0, has no caster between it and the light (shaders/common/shadow.glsl counts it lit). A directional
// light looks along its direction with an orthographic projection; a point light looks from its position
// toward the casters' centre with the perspective frustum that holds them. Clip conventions: in a light's
// tile u = 0.5 + 0.5·ndc.x, v = 0.5 − 0.5·ndc.y (row 0 at the top), depth 0 .. 1; the stored depth is the
// first caster surface along the light ray, without bias. Method and limits: docs/real-time-rendering.md,
// "Obstacles and shadows".
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/image.h"
#include "render/volume.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Pipeline;
class PipelineCache;
class Sequence;
}  // namespace sixway::gpu

namespace sixway::render {

class ObstacleMeshes;

inline constexpr uint32_t kDefaultShadowTileSize = 1024;

// Atlas tiles a scene needs: one per light with shadows = true, when at least one obstacle casts shadows.
uint32_t shadowTileCount(std::span<const scene::Light> lights, const std::vector<scene::Obstacle>& obstacles);

// World → the light's clip space for a tile of tileSize² texels, fitted to the casters' bounds and reaching
// the far side of the scene bounds; none for a point light that does not have the whole casters' box in front
// of it (inside that box, or beside it so that its nearest corner is nearer than 1/1000 of the farthest
// scene depth): there is no cube map.
std::optional<glm::mat4> shadowProjection(const scene::Light& light, const Box& casters, const Box& scene,
                                          uint32_t tileSize);

class ShadowMaps {
 public:
  // An atlas of `tiles` tiles of tileSize² texels (1 × 1 without tiles). Throws io::InputError when the atlas
  // is taller than the device's largest image, or tileSize is 0.
  ShadowMaps(const gpu::Context& context, const gpu::PipelineCache& cache, uint32_t tileSize, uint32_t tiles);
  ~ShadowMaps();

  // Per frame: the lights as they are this frame (sceneLights), the scene bounds (sceneBounds) and the
  // meshes, placed for this frame (their casterBounds are fitted). Lights with shadows = true take the tiles
  // in order while some obstacle casts shadows and tiles remain (an atlas of 0 tiles: no shadows at all); a
  // point light whose projection does not exist this frame (see shadowProjection) has no tile this frame, and
  // a note says so once per light.
  void update(std::span<const scene::Light> lights, const Box& sceneBounds, const ObstacleMeshes& meshes);

  // Stage "shadow maps": clears the atlas to 1 and draws the shadow-casting obstacles into each tile.
  void record(gpu::Sequence& sequence, const ObstacleMeshes& meshes) const;

  const gpu::Image& atlas() const { return atlas_; }
  // The atlas' width: the tile size, 1 without tiles.
  uint32_t tileSize() const { return atlas_.desc().width; }
  uint32_t tileCount() const { return tiles_; }
  // Of the last update: the tile of light `light` (index into its lights), −1 for none; the light's
  // view-projection (meaningful where it has a tile).
  int tileOf(size_t light) const;
  glm::mat4 lightViewProjection(size_t light) const;
  // Notes not yet taken (e.g. "lights[1]: point light inside or beside the shadow-casting obstacles' bounds:
  // ..."), for the command line to print.
  std::vector<std::string> takeNotes();

 private:
  uint32_t tileSize_, tiles_;
  gpu::Image atlas_;
  gpu::Buffer matrices_;  // one mat4 per tile (shadow_depth.vert)
  std::unique_ptr<gpu::Pipeline> pipeline_;
  std::vector<int> tileOf_;
  std::vector<glm::mat4> lightMatrices_;
  std::set<size_t> noted_;
  std::vector<std::string> notes_;
};

}  // namespace sixway::render
