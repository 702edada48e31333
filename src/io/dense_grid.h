#pragma once
// A scalar field on a dense, axis-aligned lattice: what the simulation exports, VDB files are resampled to
// and the renderers upload.
#include <cstddef>
#include <glm/glm.hpp>
#include <vector>

namespace sixway::io {

// A dense grid: cell (i, j, k) has its centre at origin + (i + 0.5, j + 0.5, k + 0.5) * dx.
struct DenseGrid {
  glm::ivec3 size{0};
  glm::vec3 origin{0.0f};     // world position of the corner of cell (0, 0, 0)
  glm::vec3 dx{1.0f};         // cell size per axis
  std::vector<float> values;  // x fastest, then y, then z

  std::size_t index(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * size.y + j) * size.x + i;
  }
  float& at(int i, int j, int k) { return values[index(i, j, k)]; }
  float at(int i, int j, int k) const { return values[index(i, j, k)]; }
  glm::vec3 cellCentre(int i, int j, int k) const { return origin + (glm::vec3(i, j, k) + 0.5f) * dx; }
};

}  // namespace sixway::io
