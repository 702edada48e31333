#pragma once
// Wavefront OBJ meshes (obstacles): read as positions and triangles (materials, normals and texture
// coordinates are ignored); written with a normal per vertex, for other renderers (Blender's Cycles).
#include <filesystem>
#include <glm/glm.hpp>
#include <string>
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

// One named object of a written file: triangles counter-clockwise seen from outside, a unit normal per
// position.
struct ObjObject {
  std::string name;
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::uvec3> triangles;  // indices into positions (and normals)
};

// Writes the objects ("o NAME", "v", "vn", "f a//a b//b c//c", 1-based indices running over the file; nine
// significant digits), atomically. Throws InputError naming the file when it cannot be written.
void writeObj(const std::filesystem::path& path, const std::vector<ObjObject>& objects);

}  // namespace sixway::io
