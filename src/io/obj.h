#pragma once
// Wavefront OBJ meshes (obstacles): positions and triangles only; materials, normals and texture coordinates
// are ignored.
#include <filesystem>
#include <glm/glm.hpp>
#include <vector>

namespace sixway::io {

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::uvec3> triangles;           // indices into positions
  glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};  // of all positions
};

// All shapes of the file merged into one mesh, polygons triangulated. Throws InputError naming the file for a
// missing file, a parse error, a vertex line without three finite numbers, a face that refers to a vertex
// that does not exist, or a file with no triangles.
Mesh readObj(const std::filesystem::path& path);

}  // namespace sixway::io
