#include "render/obstacle_bvh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <limits>
#include <numeric>

#include "render/obstacle_meshes.h"

namespace sixway::render {
namespace {

constexpr uint32_t kLeafTriangles = 4;
constexpr int kSahBins = 12;
constexpr float kInfinity = std::numeric_limits<float>::infinity();

Box emptyBox() {
  return {glm::vec3(kInfinity), glm::vec3(-kInfinity)};
}

void grow(Box& box, glm::vec3 p) {
  box.min = glm::min(box.min, p);
  box.max = glm::max(box.max, p);
}

void grow(Box& box, const Box& other) {
  box.min = glm::min(box.min, other.min);
  box.max = glm::max(box.max, other.max);
}

float area(const Box& box) {
  const glm::vec3 d = glm::max(box.max - box.min, glm::vec3(0.0f));
  return d.x * d.y + d.y * d.z + d.z * d.x;
}

// Builds one obstacle's hierarchy over `tris` (reordered in place) with binned surface-area splits (Wald
// 2007, "On fast Construction of SAH-based Bounding Volume Hierarchies"), nodes appended to `nodes`.
class Builder {
 public:
  Builder(std::vector<BvhTriangle>& tris, std::vector<BvhNode>& nodes, uint32_t firstTriangle)
      : tris_(tris), nodes_(nodes), first_(firstTriangle) {}

  // The root's index.
  uint32_t build(uint32_t count) {
    const uint32_t root = uint32_t(nodes_.size());
    nodes_.push_back({});
    split(root, first_, count);
    return root;
  }

 private:
  Box bounds(const BvhTriangle& t) const {
    Box b = emptyBox();
    grow(b, glm::vec3(t.p0));
    grow(b, glm::vec3(t.p1));
    grow(b, glm::vec3(t.p2));
    return b;
  }
  glm::vec3 centroid(const BvhTriangle& t) const {
    return (glm::vec3(t.p0) + glm::vec3(t.p1) + glm::vec3(t.p2)) / 3.0f;
  }

  void split(uint32_t node, uint32_t first, uint32_t count) {
    Box box = emptyBox(), centres = emptyBox();
    for (uint32_t i = first; i < first + count; ++i) {
      grow(box, bounds(tris_[i]));
      grow(centres, centroid(tris_[i]));
    }
    nodes_[node] = {box.min, first, box.max, count};
    if (count <= kLeafTriangles) return;

    // The cheapest of the bins' planes along the centroids' longest axis, against not splitting.
    const glm::vec3 extent = centres.max - centres.min;
    const int axis = extent.x > extent.y ? (extent.x > extent.z ? 0 : 2) : (extent.y > extent.z ? 1 : 2);
    if (!(extent[axis] > 0.0f)) return;  // all centroids at one point: a leaf
    std::array<Box, kSahBins> binBox;
    std::array<uint32_t, kSahBins> binCount{};
    binBox.fill(emptyBox());
    const float scale = kSahBins / extent[axis];
    const auto binOf = [&](const BvhTriangle& t) {
      return std::min(kSahBins - 1, int((centroid(t)[axis] - centres.min[axis]) * scale));
    };
    for (uint32_t i = first; i < first + count; ++i) {
      const int b = binOf(tris_[i]);
      ++binCount[b];
      grow(binBox[b], bounds(tris_[i]));
    }
    float bestCost = kInfinity;
    int bestPlane = -1;
    for (int plane = 1; plane < kSahBins; ++plane) {
      Box left = emptyBox(), right = emptyBox();
      uint32_t nLeft = 0, nRight = 0;
      for (int b = 0; b < plane; ++b) grow(left, binBox[b]), nLeft += binCount[b];
      for (int b = plane; b < kSahBins; ++b) grow(right, binBox[b]), nRight += binCount[b];
      if (!nLeft || !nRight) continue;
      const float cost = area(left) * float(nLeft) + area(right) * float(nRight);
      if (cost < bestCost) bestCost = cost, bestPlane = plane;
    }
    if (bestPlane < 0) return;
    const auto middle = std::partition(tris_.begin() + first, tris_.begin() + first + count,
                                       [&](const BvhTriangle& t) { return binOf(t) < bestPlane; });
    const uint32_t leftCount = uint32_t(middle - (tris_.begin() + first));
    const uint32_t children = uint32_t(nodes_.size());
    nodes_.push_back({});
    nodes_.push_back({});
    nodes_[node].leftOrFirst = children;
    nodes_[node].count = 0;
    split(children, first, leftCount);
    split(children + 1, first + leftCount, count - leftCount);
  }

  std::vector<BvhTriangle>& tris_;
  std::vector<BvhNode>& nodes_;
  uint32_t first_;
};

// The ray's entry and exit distances through the box (entry > exit: missed).
glm::vec2 slabs(glm::vec3 o, glm::vec3 invW, glm::vec3 lo, glm::vec3 hi) {
  const glm::vec3 a = (lo - o) * invW, b = (hi - o) * invW;
  const glm::vec3 near = glm::min(a, b), far = glm::max(a, b);
  return {std::max(near.x, std::max(near.y, near.z)), std::min(far.x, std::min(far.y, far.z))};
}

glm::vec3 safeInverse(glm::vec3 w) {
  glm::vec3 inv;
  for (int a = 0; a < 3; ++a) inv[a] = 1.0f / (std::abs(w[a]) > 1e-20f ? w[a] : std::copysign(1e-20f, w[a]));
  return inv;
}

// Möller–Trumbore: t and the barycentrics (u, v) of corners 1 and 2, or t = inf.
glm::vec3 intersect(const BvhTriangle& tri, glm::vec3 o, glm::vec3 w) {
  const glm::vec3 p0(tri.p0), e1 = glm::vec3(tri.p1) - p0, e2 = glm::vec3(tri.p2) - p0;
  const glm::vec3 p = glm::cross(w, e2);
  const float det = glm::dot(e1, p);
  if (std::abs(det) < 1e-20f) return glm::vec3(kInfinity);
  const float inv = 1.0f / det;
  const glm::vec3 s = o - p0;
  const float u = glm::dot(s, p) * inv;
  if (u < 0.0f || u > 1.0f) return glm::vec3(kInfinity);
  const glm::vec3 q = glm::cross(s, e1);
  const float v = glm::dot(w, q) * inv;
  if (v < 0.0f || u + v > 1.0f) return glm::vec3(kInfinity);
  return {glm::dot(e2, q) * inv, u, v};
}

}  // namespace

ObstacleBvh::ObstacleBvh(const gpu::Context& context, const std::vector<scene::Obstacle>& obstacles)
    : obstacles_(obstacles) {
  for (uint32_t i = 0; i < obstacles.size(); ++i) {
    const ObstacleTriangles mesh = triangulate(obstacles[i], i);
    const uint32_t first = uint32_t(triangles_.size());
    Box local = emptyBox();
    for (size_t k = 0; k + 2 < mesh.indices.size(); k += 3) {
      const ObstacleVertex &a = mesh.vertices[mesh.indices[k]], &b = mesh.vertices[mesh.indices[k + 1]],
                           &c = mesh.vertices[mesh.indices[k + 2]];
      triangles_.push_back({glm::vec4(a.position, 0.0f), glm::vec4(b.position, 0.0f),
                            glm::vec4(c.position, 0.0f), glm::vec4(a.normal, 0.0f), glm::vec4(b.normal, 0.0f),
                            glm::vec4(c.normal, 0.0f)});
      for (const ObstacleVertex* v : {&a, &b, &c}) grow(local, v->position);
    }
    const uint32_t root = Builder(triangles_, nodes_, first).build(uint32_t(triangles_.size()) - first);
    localBounds_.push_back(local);
    ObstacleRecord record;
    record.placement.w = float(root);
    record.boundsMin.w = obstacles[i].shadows ? 1.0f : 0.0f;
    records_.push_back(record);
  }
  if (obstacles.empty()) return;
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  nodeBuffer_ = gpu::Buffer(context, nodes_.size() * sizeof(BvhNode), storage, gpu::MemoryKind::Device,
                            "obstacle hierarchy nodes");
  nodeBuffer_.upload(nodes_);
  triangleBuffer_ = gpu::Buffer(context, triangles_.size() * sizeof(BvhTriangle), storage,
                                gpu::MemoryKind::Device, "obstacle hierarchy triangles");
  triangleBuffer_.upload(triangles_);
  recordBuffer_ =
      gpu::Buffer(context, records_.size() * sizeof(ObstacleRecord), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                  gpu::MemoryKind::FrameParameters, "obstacle placements for rays");
  update(0.0);
}

void ObstacleBvh::update(double seconds) {
  if (obstacles_.empty()) return;
  for (size_t i = 0; i < obstacles_.size(); ++i) {
    const glm::vec3 placed = placementAt(obstacles_[i], seconds);
    ObstacleRecord& r = records_[i];
    r.placement = glm::vec4(placed, r.placement.w);
    r.boundsMin = glm::vec4(placed + localBounds_[i].min, r.boundsMin.w);
    r.boundsMax = glm::vec4(placed + localBounds_[i].max, 0.0f);
  }
  recordBuffer_.upload(records_);
}

std::optional<ObstacleHit> ObstacleBvh::nearestHit(glm::vec3 o, glm::vec3 w, float tMin, float tMax,
                                                   bool castersOnly) const {
  const glm::vec3 invW = safeInverse(w);
  std::optional<ObstacleHit> best;
  float tBest = tMax;
  for (uint32_t k = 0; k < records_.size(); ++k) {
    const ObstacleRecord& r = records_[k];
    if (castersOnly && r.boundsMin.w == 0.0f) continue;
    const glm::vec2 span = slabs(o, invW, glm::vec3(r.boundsMin), glm::vec3(r.boundsMax));
    if (span.x > span.y || span.y <= tMin || span.x >= tBest) continue;
    const glm::vec3 local = o - glm::vec3(r.placement);
    std::vector<uint32_t> stack{uint32_t(r.placement.w)};
    while (!stack.empty()) {
      const BvhNode& node = nodes_[stack.back()];
      stack.pop_back();
      const glm::vec2 box = slabs(local, invW, node.min, node.max);
      if (box.x > box.y || box.y <= tMin || box.x >= tBest) continue;
      if (node.count == 0) {
        stack.push_back(node.leftOrFirst);
        stack.push_back(node.leftOrFirst + 1);
        continue;
      }
      for (uint32_t i = node.leftOrFirst; i < node.leftOrFirst + node.count; ++i) {
        const glm::vec3 hit = intersect(triangles_[i], local, w);
        if (!(hit.x > tMin && hit.x < tBest)) continue;
        tBest = hit.x;
        const BvhTriangle& t = triangles_[i];
        const glm::vec3 n =
            (1.0f - hit.y - hit.z) * glm::vec3(t.n0) + hit.y * glm::vec3(t.n1) + hit.z * glm::vec3(t.n2);
        best = ObstacleHit{hit.x, glm::normalize(n), k};
      }
    }
  }
  return best;
}

}  // namespace sixway::render
