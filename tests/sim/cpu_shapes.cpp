#include "cpu_shapes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <utility>

namespace sixway::test {

ShapeTest sphereTest(glm::dvec3 p, glm::dvec3 centre, double radius) {
  const double distance = glm::length(p - centre);
  return {distance <= radius, std::abs(distance - radius)};
}

ShapeTest cylinderTest(glm::dvec3 p, glm::dvec3 centre, glm::dvec3 axis, double radius, double halfHeight) {
  const glm::dvec3 d = p - centre;
  const double along = glm::dot(d, axis);
  const double across = glm::length(d - along * axis);
  return {std::abs(along) <= halfHeight && across <= radius,
          std::min(std::abs(std::abs(along) - halfHeight), std::abs(across - radius))};
}

ShapeTest capsuleTest(glm::dvec3 p, glm::dvec3 centre, glm::dvec3 axis, double radius, double halfSegment) {
  const glm::dvec3 d = p - centre;
  const double distance = glm::length(d - std::clamp(glm::dot(d, axis), -halfSegment, halfSegment) * axis);
  return {distance <= radius, std::abs(distance - radius)};
}

ShapeTest boxTest(glm::dvec3 p, glm::dvec3 centre, glm::dvec3 halfSize) {
  const glm::dvec3 slack = halfSize - glm::abs(p - centre);
  return {glm::all(glm::greaterThanEqual(slack, glm::dvec3(0))),
          std::min({std::abs(slack.x), std::abs(slack.y), std::abs(slack.z)})};
}

glm::dmat3 eulerXyz(glm::dvec3 degrees) {
  const glm::dvec3 r = degrees * (std::numbers::pi / 180);
  const double cx = std::cos(r.x), sx = std::sin(r.x), cy = std::cos(r.y), sy = std::sin(r.y);
  const double cz = std::cos(r.z), sz = std::sin(r.z);
  // glm matrices are column-major: each triple below is a column.
  const glm::dmat3 rx(1, 0, 0, 0, cx, sx, 0, -sx, cx);
  const glm::dmat3 ry(cy, 0, -sy, 0, 1, 0, sy, 0, cy);
  const glm::dmat3 rz(cz, sz, 0, -sz, cz, 0, 0, 0, 1);
  return rz * ry * rx;
}

WorldMesh placeMesh(const io::Mesh& mesh, double scale, glm::dvec3 translate, glm::dvec3 rotateDeg) {
  const glm::dmat3 rotation = eulerXyz(rotateDeg);
  WorldMesh out;
  for (const glm::vec3& p : mesh.positions)
    out.positions.push_back(translate + rotation * (scale * glm::dvec3(p)));
  out.triangles = mesh.triangles;
  return out;
}

ShapeTest convexMeshTest(glm::dvec3 p, const WorldMesh& mesh) {
  ShapeTest result{true, INFINITY};
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
    const double height = glm::dot(glm::normalize(glm::cross(b - a, c - a)), p - a);
    result.inside = result.inside && height <= 0;
    result.margin = std::min(result.margin, std::abs(height));
  }
  return result;
}

double enclosedVolume(const WorldMesh& mesh) {
  // Edges of one triangle only are the rims of the holes.
  std::map<std::pair<unsigned, unsigned>, int> edges;
  for (const glm::uvec3& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) ++edges[std::minmax(t[e], t[(e + 1) % 3])];
  glm::dvec3 origin(0);
  std::set<unsigned> rim;
  for (const auto& [edge, uses] : edges)
    if (uses == 1) rim.insert({edge.first, edge.second});
  for (unsigned vertex : rim) origin += mesh.positions[vertex];
  if (!rim.empty()) origin /= double(rim.size());

  double sum = 0;
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3 a = mesh.positions[t.x] - origin, b = mesh.positions[t.y] - origin,
                     c = mesh.positions[t.z] - origin;
    sum += glm::dot(a, glm::cross(b, c));
  }
  return sum / 6;
}

}  // namespace sixway::test
