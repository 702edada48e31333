#include "render/obstacle_meshes.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <limits>
#include <numbers>
#include <utility>

#include "io/obj.h"
#include "scene/obstacle_placement.h"

namespace sixway::render {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// Clang 14 (the fuzz build) does not deduce aggregate template arguments without a guide.
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

// Two unit vectors completing `axis` to a right-handed frame (u × v = axis).
void perpendiculars(glm::vec3 axis, glm::vec3& u, glm::vec3& v) {
  const glm::vec3 other = std::abs(axis.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  u = glm::normalize(glm::cross(other, axis));
  v = glm::cross(axis, u);
}

class Builder {
 public:
  explicit Builder(uint32_t obstacle) : obstacle_(obstacle) {}
  uint32_t vertex(glm::vec3 position, glm::vec3 normal) {
    out_.vertices.push_back({position, obstacle_, normal, 0.0f});
    return uint32_t(out_.vertices.size() - 1);
  }
  void triangle(uint32_t a, uint32_t b, uint32_t c) { out_.indices.insert(out_.indices.end(), {a, b, c}); }
  void quad(uint32_t a, uint32_t b, uint32_t c, uint32_t d) {  // counter-clockwise
    triangle(a, b, c);
    triangle(a, c, d);
  }
  ObstacleTriangles take() { return std::move(out_); }

 private:
  uint32_t obstacle_;
  ObstacleTriangles out_;
};

// Latitude rings from pole to pole, kRoundSegments around; the poles' degenerate triangles are left out.
ObstacleTriangles sphere(const scene::SphereObstacle& s, uint32_t index) {
  constexpr int around = kRoundSegments, rings = kRoundSegments / 2;
  Builder b(index);
  for (int j = 0; j <= rings; ++j) {
    const float theta = kPi * float(j) / rings;  // from +y
    for (int i = 0; i <= around; ++i) {
      const float phi = 2.0f * kPi * float(i) / around;
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
      b.vertex(s.radius * n, n);
    }
  }
  const auto at = [](int j, int i) { return uint32_t(j * (around + 1) + i); };
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < around; ++i) {
      if (j > 0) b.triangle(at(j, i), at(j + 1, i), at(j, i + 1));
      if (j < rings - 1) b.triangle(at(j, i + 1), at(j + 1, i), at(j + 1, i + 1));
    }
  return b.take();
}

// The side with radial normals and two flat caps.
ObstacleTriangles cylinder(const scene::CylinderObstacle& c, uint32_t index) {
  glm::vec3 u, v;
  perpendiculars(c.axis, u, v);
  const glm::vec3 half = 0.5f * c.height * c.axis;
  Builder b(index);
  const auto radial = [&](int i) {
    const float phi = 2.0f * kPi * float(i) / kRoundSegments;
    return std::cos(phi) * u + std::sin(phi) * v;
  };
  for (int i = 0; i < kRoundSegments; ++i) {
    const glm::vec3 n0 = radial(i), n1 = radial(i + 1);
    const uint32_t a = b.vertex(c.radius * n0 - half, n0), d = b.vertex(c.radius * n0 + half, n0);
    const uint32_t bb = b.vertex(c.radius * n1 - half, n1), cc = b.vertex(c.radius * n1 + half, n1);
    b.quad(a, bb, cc, d);
  }
  for (float side : {-1.0f, 1.0f}) {
    const glm::vec3 n = side * c.axis;
    const uint32_t centre = b.vertex(side * half, n);
    for (int i = 0; i < kRoundSegments; ++i) {
      const uint32_t p0 = b.vertex(c.radius * radial(i) + side * half, n);
      const uint32_t p1 = b.vertex(c.radius * radial(i + 1) + side * half, n);
      if (side > 0)
        b.triangle(centre, p0, p1);
      else
        b.triangle(centre, p1, p0);
    }
  }
  return b.take();
}

// The sphere's latitude rings in the capsule's frame (the axis as the sphere's +y), the upper half moved up
// the segment and the lower half down; the equator ring, once on each end, bounds the side.
ObstacleTriangles capsule(const scene::CapsuleObstacle& c, uint32_t index) {
  constexpr int around = kRoundSegments, rings = kRoundSegments / 2, rows = rings + 2;
  glm::vec3 u, v;
  perpendiculars(c.axis, u, v);
  const glm::vec3 half = (0.5f * c.height - c.radius) * c.axis;
  Builder b(index);
  for (int row = 0; row < rows; ++row) {
    const bool upper = row <= rings / 2;
    const float theta = kPi * float(upper ? row : row - 1) / rings;  // from +axis
    for (int i = 0; i <= around; ++i) {
      const float phi = 2.0f * kPi * float(i) / around;
      const glm::vec3 n = std::sin(theta) * std::cos(phi) * u + std::cos(theta) * c.axis +
                          std::sin(theta) * std::sin(phi) * v;
      b.vertex(c.radius * n + (upper ? half : -half), n);
    }
  }
  const auto at = [](int row, int i) { return uint32_t(row * (around + 1) + i); };
  for (int row = 0; row + 1 < rows; ++row)
    for (int i = 0; i < around; ++i) {
      if (row > 0) b.triangle(at(row, i), at(row + 1, i), at(row, i + 1));
      if (row < rows - 2) b.triangle(at(row, i + 1), at(row + 1, i), at(row + 1, i + 1));
    }
  return b.take();
}

ObstacleTriangles box(const scene::BoxObstacle& box, uint32_t index) {
  const glm::vec3 h = 0.5f * box.size;
  Builder b(index);
  for (int axis = 0; axis < 3; ++axis)
    for (float side : {-1.0f, 1.0f}) {
      glm::vec3 n(0.0f);
      n[axis] = side;
      // Two face axes with s × t = n.
      glm::vec3 s(0.0f), t(0.0f);
      s[(axis + 1) % 3] = 1.0f;
      t[(axis + 2) % 3] = side;
      const glm::vec3 centre = n * h, hs = s * h, ht = t * h;
      b.quad(b.vertex(centre - hs - ht, n), b.vertex(centre + hs - ht, n), b.vertex(centre + hs + ht, n),
             b.vertex(centre - hs + ht, n));
    }
  return b.take();
}

// The OBJ triangles scaled and turned. A corner's normal is the area-weighted sum of the normals of the faces
// around its vertex that turn from its own face by less than the crease angle; corners of a vertex with equal
// normals share one output vertex.
ObstacleTriangles mesh(const scene::MeshObstacle& m, uint32_t index) {
  const io::Mesh obj = scene::meshTriangles(m);
  const glm::mat3 turn = scene::meshRotation(m) * m.scale;
  std::vector<glm::vec3> positions(obj.positions.size());
  std::transform(obj.positions.begin(), obj.positions.end(), positions.begin(),
                 [&](glm::vec3 p) { return turn * p; });

  std::vector<glm::vec3> areaNormals(obj.triangles.size());  // |n| = twice the area
  std::vector<std::vector<uint32_t>> facesOf(positions.size());
  for (uint32_t f = 0; f < obj.triangles.size(); ++f) {
    const glm::uvec3 t = obj.triangles[f];
    areaNormals[f] = glm::cross(positions[t.y] - positions[t.x], positions[t.z] - positions[t.x]);
    for (int k = 0; k < 3; ++k) facesOf[t[k]].push_back(f);
  }
  const float cosCrease = std::cos(glm::radians(45.0f));
  const auto unit = [](glm::vec3 n) { return glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0.0f); };

  Builder b(index);
  std::vector<std::vector<std::pair<glm::vec3, uint32_t>>> emitted(positions.size());
  for (uint32_t f = 0; f < obj.triangles.size(); ++f) {
    const glm::vec3 own = unit(areaNormals[f]);
    uint32_t corners[3];
    for (int k = 0; k < 3; ++k) {
      const uint32_t p = obj.triangles[f][k];
      glm::vec3 sum(0.0f);
      for (uint32_t g : facesOf[p])
        if (glm::dot(own, unit(areaNormals[g])) >= cosCrease) sum += areaNormals[g];
      const glm::vec3 normal = glm::length(sum) > 0.0f ? glm::normalize(sum) : glm::vec3(0, 1, 0);
      auto& known = emitted[p];
      auto same = std::find_if(known.begin(), known.end(), [&](const auto& e) { return e.first == normal; });
      if (same == known.end()) same = known.insert(known.end(), {normal, b.vertex(positions[p], normal)});
      corners[k] = same->second;
    }
    b.triangle(corners[0], corners[1], corners[2]);
  }
  return b.take();
}

}  // namespace

ObstacleTriangles triangulate(const scene::Obstacle& obstacle, uint32_t index) {
  return std::visit(Overloaded{[&](const scene::SphereObstacle& s) { return sphere(s, index); },
                               [&](const scene::CylinderObstacle& c) { return cylinder(c, index); },
                               [&](const scene::BoxObstacle& x) { return box(x, index); },
                               [&](const scene::MeshObstacle& m) { return mesh(m, index); },
                               [&](const scene::CapsuleObstacle& c) { return capsule(c, index); }},
                    obstacle.shape);
}

glm::vec3 placementAt(const scene::Obstacle& obstacle, double seconds) {
  if (obstacle.motion) return scene::evaluateMotion(*obstacle.motion, seconds).position;
  return std::visit(Overloaded{[](const scene::SphereObstacle& s) { return s.center; },
                               [](const scene::CylinderObstacle& c) { return c.center; },
                               [](const scene::BoxObstacle& x) { return x.center; },
                               [](const scene::MeshObstacle& m) { return m.translate; },
                               [](const scene::CapsuleObstacle& c) { return c.center; }},
                    obstacle.shape);
}

std::vector<io::ObjObject> placedObstacles(const std::vector<scene::Obstacle>& obstacles, double seconds) {
  std::vector<io::ObjObject> objects;
  for (uint32_t i = 0; i < obstacles.size(); ++i) {
    const ObstacleTriangles triangles = triangulate(obstacles[i], i);
    const glm::vec3 placement = placementAt(obstacles[i], seconds);
    io::ObjObject& object = objects.emplace_back();
    object.name = "obstacle_" + std::to_string(i);
    for (const ObstacleVertex& v : triangles.vertices) {
      object.positions.push_back(placement + v.position);
      object.normals.push_back(v.normal);
    }
    for (size_t k = 0; k + 2 < triangles.indices.size(); k += 3)
      object.triangles.emplace_back(triangles.indices[k], triangles.indices[k + 1], triangles.indices[k + 2]);
  }
  return objects;
}

ObstacleMeshes::ObstacleMeshes(const gpu::Context& context, const std::vector<scene::Obstacle>& obstacles,
                               gpu::MemoryKind memory)
    : obstacles_(obstacles), placed_(obstacles.size()) {
  std::vector<ObstacleVertex> vertices;
  std::vector<uint32_t> indices;
  for (bool casters : {true, false})
    for (uint32_t i = 0; i < obstacles.size(); ++i) {
      if (obstacles[i].shadows != casters) continue;
      ObstacleTriangles t = triangulate(obstacles[i], i);
      const uint32_t base = uint32_t(vertices.size());
      for (uint32_t k : t.indices) indices.push_back(base + k);
      vertices.insert(vertices.end(), t.vertices.begin(), t.vertices.end());
      if (casters) casterIndexCount_ = uint32_t(indices.size());
    }
  localBounds_.assign(obstacles.size(), Box{glm::vec3(std::numeric_limits<float>::max()),
                                            glm::vec3(std::numeric_limits<float>::lowest())});
  for (const ObstacleVertex& v : vertices) {
    Box& b = localBounds_[v.obstacle];
    b.min = glm::min(b.min, v.position);
    b.max = glm::max(b.max, v.position);
  }
  indexCount_ = uint32_t(indices.size());
  if (obstacles.empty()) return;
  vertices_ = gpu::Buffer(context, vertices.size() * sizeof(ObstacleVertex),
                          VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, memory,
                          "obstacle vertices");
  vertices_.upload(vertices);
  indices_ = gpu::Buffer(context, indices.size() * sizeof(uint32_t),
                         VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, memory,
                         "obstacle indices");
  indices_.upload(indices);
  placements_ = gpu::Buffer(context, obstacles.size() * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                            gpu::MemoryKind::FrameParameters, "obstacle placements");
  update(0.0);
}

void ObstacleMeshes::update(double seconds) {
  if (obstacles_.empty()) return;
  std::vector<glm::vec4> placements(obstacles_.size());
  for (size_t i = 0; i < obstacles_.size(); ++i) {
    placed_[i] = placementAt(obstacles_[i], seconds);
    placements[i] = glm::vec4(placed_[i], 0.0f);
  }
  placements_.upload(placements);
}

Box ObstacleMeshes::bounds() const {
  return boundsOf(false);
}

Box ObstacleMeshes::casterBounds() const {
  return boundsOf(true);
}

Box ObstacleMeshes::boundsOf(bool castersOnly) const {
  Box all{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(std::numeric_limits<float>::lowest())};
  for (size_t i = 0; i < obstacles_.size(); ++i) {
    if (castersOnly && !obstacles_[i].shadows) continue;
    all.min = glm::min(all.min, placed_[i] + localBounds_[i].min);
    all.max = glm::max(all.max, placed_[i] + localBounds_[i].max);
  }
  return all;
}

std::vector<gpu::VertexAttribute> ObstacleMeshes::vertexAttributes() {
  return {{0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(ObstacleVertex, position)},
          {1, VK_FORMAT_R32_UINT, offsetof(ObstacleVertex, obstacle)},
          {2, VK_FORMAT_R32G32B32_SFLOAT, offsetof(ObstacleVertex, normal)}};
}

double sphereFacetDepth(double radius) {
  const double delta = 2 * std::numbers::pi / kRoundSegments;
  return radius * (1 - std::cos(delta / std::sqrt(2.0)));
}

Box domainBox(const scene::Grid& grid) {
  return {grid.origin, grid.origin + glm::vec3(grid.size) * grid.cellSize};
}

Box sceneBounds(const Box& domain, const ObstacleMeshes& meshes) {
  if (meshes.empty()) return domain;
  const Box obstacles = meshes.bounds();
  return {glm::min(domain.min, obstacles.min), glm::max(domain.max, obstacles.max)};
}

}  // namespace sixway::render
