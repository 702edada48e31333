#pragma once
// The scene's obstacles as triangle meshes for the rasterized passes (the lit obstacles, the shadow maps):
// spheres, capped cylinders, boxes and OBJ meshes triangulated once on the host, with normals, around each
// obstacle's placement point (a shape's centre, a mesh's translation). Obstacles move rigidly without turning
// (docs/scene-format.md, motion), so a frame only changes one translation per obstacle: update() writes them
// into a host-visible buffer that the recorded draws read, at the positions the simulation voxelizes
// (scene::evaluateMotion). Method and measured errors: docs/real-time-rendering.md, "Obstacles and shadows".
#include <cstdint>
#include <glm/vec3.hpp>
#include <optional>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/pipeline.h"
#include "io/obj.h"
#include "render/volume.h"
#include "scene/scene.h"

namespace sixway::render {

// One vertex as obstacle.vert and shadow_depth.vert read it (shaders/render/obstacle_vertex.glsl).
struct ObstacleVertex {
  glm::vec3 position{0.0f};  // world offset from the obstacle's placement point
  uint32_t obstacle = 0;     // index into the scene's obstacles (and the placement buffer)
  glm::vec3 normal{0.0f};    // unit, outward
  float unused = 0.0f;
};
static_assert(sizeof(ObstacleVertex) == 32);

// Segments around a sphere (and half as many from pole to pole) or a cylinder. The polygon lies inside the
// circle by at most r·(1 − cos(π/64)) = 0.0012·r: under a pixel while the radius spans under 800 pixels.
inline constexpr int kRoundSegments = 64;

// How far a flat triangle of a sphere's tessellation lies inside the sphere at most: its vertices are on the
// sphere and its circumcircle spans at most the diagonal of a Δ × Δ cell (Δ = 2π / kRoundSegments), so the
// deepest point is r·(1 − cos(Δ/√2)) below the surface (0.0024·r).
double sphereFacetDepth(double radius);

// The triangles of one obstacle around its placement point; vertices' `obstacle` is `index`. Meshes are read
// from their OBJ file and scaled and turned as the scene says (world = translate + Rz·Ry·Rx·(scale·p));
// their normals are smoothed across edges whose faces turn by less than 45°. Throws io::InputError for an OBJ
// file that cannot be read.
struct ObstacleTriangles {
  std::vector<ObstacleVertex> vertices;
  std::vector<uint32_t> indices;  // three per triangle, counter-clockwise seen from outside
};
ObstacleTriangles triangulate(const scene::Obstacle& obstacle, uint32_t index);

// The placement point of an obstacle at `seconds` (time = frame · frame_dt): its motion's position, else the
// shape's centre or the mesh's translation.
glm::vec3 placementAt(const scene::Obstacle& obstacle, double seconds);

// Every obstacle's triangles in world space at `seconds`, as the passes and the path tracer see them, one
// object each ("obstacle_<index>"): what `sixway sim --vdb-out` writes beside each frame for other renderers.
std::vector<io::ObjObject> placedObstacles(const std::vector<scene::Obstacle>& obstacles, double seconds);

class ObstacleMeshes {
 public:
  // Triangulates all obstacles once and places them at time 0. Obstacles with shadows = true come first in
  // the index buffer, so that the shadow pass draws just the first casterIndexCount() indices. `memory`:
  // where the vertices and indices live (host-visible memory takes them without a submission).
  ObstacleMeshes(const gpu::Context& context, const std::vector<scene::Obstacle>& obstacles,
                 gpu::MemoryKind memory = gpu::MemoryKind::Device);

  // Places the obstacles at time `seconds` (frame · frame_dt), for every pass recorded with these meshes.
  void update(double seconds);
  // Replaces the motion of obstacle `obstacle` (the simulation's steered one,
  // sim::Simulation::steerObstacle), from the next update() on.
  void setMotion(size_t obstacle, std::optional<scene::Motion> motion) {
    obstacles_.at(obstacle).motion = std::move(motion);
  }

  bool empty() const { return indexCount_ == 0; }
  uint32_t indexCount() const { return indexCount_; }
  uint32_t casterIndexCount() const { return casterIndexCount_; }
  // Vertex buffer (ObstacleVertex), index buffer (uint32) and one vec4 per obstacle (xyz: placement point);
  // none of them exists when the scene has no obstacles.
  const gpu::Buffer& vertices() const { return vertices_; }
  const gpu::Buffer& indices() const { return indices_; }
  const gpu::Buffer& placements() const { return placements_; }
  // The axis-aligned bounds of all obstacles, or of those with shadows = true, as last placed; min > max when
  // there are none.
  Box bounds() const;
  Box casterBounds() const;

  // The vertex input of ObstacleVertex for a gpu::GraphicsPipelineDesc.
  static std::vector<gpu::VertexAttribute> vertexAttributes();

 private:
  std::vector<scene::Obstacle> obstacles_;
  Box boundsOf(bool castersOnly) const;

  std::vector<Box> localBounds_;  // of each obstacle's vertices, around its placement point
  std::vector<glm::vec3> placed_;
  uint32_t indexCount_ = 0, casterIndexCount_ = 0;
  gpu::Buffer vertices_, indices_, placements_;
};

// The simulation domain: grid.origin to grid.origin + grid.size · grid.cellSize.
Box domainBox(const scene::Grid& grid);
// The domain box grown to hold the obstacles as last placed: the bounds that the shadow maps cover and whose
// boxDepthRange is the depth range of the obstacle pass (and of every pass that tests against its depth).
Box sceneBounds(const Box& domain, const ObstacleMeshes& meshes);

}  // namespace sixway::render
