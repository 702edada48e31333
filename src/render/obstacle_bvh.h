#pragma once
// The scene's obstacles for ray tracing (the path tracer's ground truth): the triangles the rasterized passes
// draw (obstacle_meshes.h: triangulate), one bounding-volume hierarchy per obstacle around its placement
// point, and per frame each obstacle's placement and world bounds. Obstacles move rigidly without turning, so
// a frame changes only the placements (update); the hierarchies are built once.
// shaders/common/obstacle_trace.glsl traverses the same layout on the GPU; nearestHit() here is its CPU
// counterpart, for tests and tools.
#include <cstdint>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <optional>
#include <vector>

#include "gpu/buffer.h"
#include "render/volume.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Context;
}

namespace sixway::render {

// As obstacle_trace.glsl reads them. A node's children are nodes leftOrFirst and leftOrFirst + 1 (count 0),
// or it is a leaf of `count` triangles from leftOrFirst on. Node indices are global (every obstacle's
// hierarchy in one array); each obstacle's root is its ObstacleRecord's.
struct BvhNode {
  glm::vec3 min{0.0f};
  uint32_t leftOrFirst = 0;
  glm::vec3 max{0.0f};
  uint32_t count = 0;
};
static_assert(sizeof(BvhNode) == 32);

// A triangle around its obstacle's placement point: its corners and their (smoothed, outward) normals.
struct BvhTriangle {
  glm::vec4 p0, p1, p2;  // w unused
  glm::vec4 n0, n1, n2;  // w unused
};
static_assert(sizeof(BvhTriangle) == 96);

// One per obstacle: where it is this frame.
struct ObstacleRecord {
  glm::vec4 placement{0.0f};  // xyz: the placement point; w: the root node's index
  glm::vec4 boundsMin{0.0f};  // xyz: world bounds this frame; w: 1 when it casts shadows
  glm::vec4 boundsMax{0.0f};
};
static_assert(sizeof(ObstacleRecord) == 48);

struct ObstacleHit {
  float t = 0.0f;
  glm::vec3 normal{0.0f};  // interpolated from the corners' normals, unit, not turned toward the ray
  uint32_t obstacle = 0;
};

class ObstacleBvh {
 public:
  // Triangulates and builds once, places at time 0. Throws io::InputError for an OBJ file that cannot be
  // read.
  ObstacleBvh(const gpu::Context& context, const std::vector<scene::Obstacle>& obstacles);

  // Places the obstacles at time `seconds` (frame · frame_dt), as ObstacleMeshes::update does.
  void update(double seconds);
  // Replaces an obstacle's motion from the next update() on (a steered obstacle).
  void setMotion(size_t obstacle, std::optional<scene::Motion> motion) {
    obstacles_.at(obstacle).motion = std::move(motion);
  }

  uint32_t obstacleCount() const { return uint32_t(records_.size()); }
  uint32_t triangleCount() const { return uint32_t(triangles_.size()); }
  // The nearest hit of the ray o + t·w with t in (tMin, tMax), among the shadow casters only when
  // `castersOnly`; the CPU mirror of obstacle_trace.glsl.
  std::optional<ObstacleHit> nearestHit(glm::vec3 o, glm::vec3 w, float tMin, float tMax,
                                        bool castersOnly = false) const;

  const std::vector<ObstacleRecord>& records() const { return records_; }
  // Device buffers (none exists without obstacles): BvhNode, BvhTriangle, and ObstacleRecord per obstacle
  // (host-visible, rewritten by update(): the frame's placements for recorded passes).
  const gpu::Buffer& nodes() const { return nodeBuffer_; }
  const gpu::Buffer& triangles() const { return triangleBuffer_; }
  const gpu::Buffer& placements() const { return recordBuffer_; }

 private:
  std::vector<scene::Obstacle> obstacles_;
  std::vector<Box> localBounds_;
  std::vector<BvhNode> nodes_;
  std::vector<BvhTriangle> triangles_;
  std::vector<ObstacleRecord> records_;
  gpu::Buffer nodeBuffer_, triangleBuffer_, recordBuffer_;
};

}  // namespace sixway::render
