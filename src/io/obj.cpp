#include "io/obj.h"

#include <tiny_obj_loader.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <span>
#include <sstream>

#include "io/error.h"
#include "io/file_access.h"

namespace sixway::io {

namespace {

std::string firstLine(const std::string& text) {
  return text.substr(0, text.find('\n'));
}

// The text after the keyword when `line` is a vertex position ("v x y z ..."), else nothing.
std::optional<std::string> vertexCoordinates(const std::string& line) {
  const std::size_t start = line.find_first_not_of(" \t");
  const bool isVertex = start != std::string::npos && start + 1 < line.size() && line[start] == 'v' &&
                        (line[start + 1] == ' ' || line[start + 1] == '\t');
  if (!isVertex) return std::nullopt;
  return line.substr(start + 2);
}

// tinyobj reads a malformed or missing coordinate as 0 without a warning, so the "v" lines are checked first.
void checkVertexLines(const std::string& source, std::istream& in) {
  std::string line;
  for (int lineNumber = 1; std::getline(in, line); ++lineNumber) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::optional<std::string> coordinates = vertexCoordinates(line);
    if (!coordinates) continue;
    std::istringstream tokens(*coordinates);
    for (int axis = 0; axis < 3; ++axis) {
      std::string token;
      char* end = nullptr;
      const double value = (tokens >> token) ? std::strtod(token.c_str(), &end) : 0.0;
      if (token.empty() || *end != '\0') {
        throw InputError(
            source, "line " + std::to_string(lineNumber) + ": a vertex needs three numbers: '" + line + "'");
      }
      if (!std::isfinite(static_cast<float>(value))) {
        throw InputError(source, "line " + std::to_string(lineNumber) + ": vertex coordinate '" + token +
                                     "' is not a finite float");
      }
    }
  }
}

}  // namespace

Mesh readObj(const std::filesystem::path& path) {
  const std::string source = path.string();
  requireRegularFile(path);
  std::ifstream in(path);
  if (!in) throw InputError(source, "cannot open the file for reading");
  checkVertexLines(source, in);
  in.clear();
  in.seekg(0);

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warning, error;
  // No material reader: "mtllib" lines are ignored, so a missing .mtl file does not matter.
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &in, nullptr, /*triangulate=*/true)) {
    throw InputError(source, "cannot parse OBJ: " + firstLine(error));
  }

  Mesh mesh;
  const std::size_t vertexCount = attrib.vertices.size() / 3;
  const InputError faceIndexError(source, "a face refers to a vertex that does not exist (the file has " +
                                              std::to_string(vertexCount) + " vertices)");
  // tinyobj only warns about faces past the vertex count, and drops such polygons when triangulating them.
  if (warning.find("out of bounds") != std::string::npos ||
      warning.find("invalid vertex index") != std::string::npos) {
    throw faceIndexError;
  }
  if (warning.find("Degenerated face") != std::string::npos) {
    throw InputError(source, "a face has fewer than 3 vertices");
  }
  for (std::size_t v = 0; v < vertexCount; ++v) {
    mesh.positions.emplace_back(attrib.vertices[3 * v], attrib.vertices[3 * v + 1],
                                attrib.vertices[3 * v + 2]);
  }

  for (const tinyobj::shape_t& shape : shapes) {
    const std::vector<tinyobj::index_t>& indices = shape.mesh.indices;
    for (std::size_t first = 0; first + 2 < indices.size(); first += 3) {
      glm::uvec3 triangle;
      for (int corner = 0; corner < 3; ++corner) {
        // Negative (relative) indices are resolved by tinyobj, but may still point before the first vertex.
        const int index = indices[first + corner].vertex_index;
        if (index < 0 || static_cast<std::size_t>(index) >= vertexCount) throw faceIndexError;
        triangle[corner] = static_cast<unsigned>(index);
      }
      mesh.triangles.push_back(triangle);
    }
  }
  if (mesh.triangles.empty()) throw InputError(source, "no triangles (no faces with 3 or more vertices)");

  mesh.boundsMin = mesh.boundsMax = mesh.positions.front();
  for (const glm::vec3& position : mesh.positions) {
    mesh.boundsMin = glm::min(mesh.boundsMin, position);
    mesh.boundsMax = glm::max(mesh.boundsMax, position);
  }
  return mesh;
}

void writeObj(const std::filesystem::path& path, const std::vector<ObjObject>& objects) {
  std::string text = "# sixway\n";
  char line[128];
  const auto vector = [&](const char* keyword, glm::vec3 v) {
    std::snprintf(line, sizeof(line), "%s %.9g %.9g %.9g\n", keyword, v.x, v.y, v.z);
    text += line;
  };
  size_t base = 1;
  for (const ObjObject& object : objects) {
    text += "o " + object.name + "\n";
    for (const glm::vec3& p : object.positions) vector("v", p);
    for (const glm::vec3& n : object.normals) vector("vn", n);
    for (const glm::uvec3& t : object.triangles) {
      const size_t a = base + t.x, b = base + t.y, c = base + t.z;
      std::snprintf(line, sizeof(line), "f %zu//%zu %zu//%zu %zu//%zu\n", a, a, b, b, c, c);
      text += line;
    }
    base += object.positions.size();
  }
  AtomicFile file(path);
  file.writeAll(std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
  file.commit();
}

}  // namespace sixway::io
