#pragma once
// CPU oracle: point-in-shape tests for the obstacle shapes, the mesh placement of docs/scene-format.md
// (world = translate + Rz·Ry·Rx · scale · p), and the volume a triangle mesh encloses. Each test also
// says how far the point is from deciding the other way (`margin`, in the units of p), so that a test
// can leave out points where float rounding may legitimately decide differently.
#include <glm/glm.hpp>
#include <vector>

#include "io/obj.h"

namespace sixway::test {

struct ShapeTest {
  bool inside = false;
  double margin = 0;  // the smallest distance to a bounding surface of the conditions tested
};

ShapeTest sphereTest(glm::dvec3 p, glm::dvec3 centre, double radius);
// `axis` unit, `halfHeight` half the length along it.
ShapeTest cylinderTest(glm::dvec3 p, glm::dvec3 centre, glm::dvec3 axis, double radius, double halfHeight);
// Within `radius` of the segment of half length `halfSegment` along the unit `axis` through `centre`.
ShapeTest capsuleTest(glm::dvec3 p, glm::dvec3 centre, glm::dvec3 axis, double radius, double halfSegment);
ShapeTest boxTest(glm::dvec3 p, glm::dvec3 centre, glm::dvec3 halfSize);

// Rz(z)·Ry(y)·Rx(x), angles in degrees: rotates about x first.
glm::dmat3 eulerXyz(glm::dvec3 degrees);

// The mesh's triangles placed in the world.
struct WorldMesh {
  std::vector<glm::dvec3> positions;
  std::vector<glm::uvec3> triangles;
};
WorldMesh placeMesh(const io::Mesh& mesh, double scale, glm::dvec3 translate, glm::dvec3 rotateDeg);

// Inside a closed convex mesh with outward-facing triangles: behind every face plane.
ShapeTest convexMeshTest(glm::dvec3 p, const WorldMesh& mesh);

// The volume enclosed by the mesh, Σ over triangles of the signed tetrahedron (a − o)·((b − o)×(c − o))/6
// (divergence theorem). An open mesh (the Stanford bunny has holes in its base) is closed by a fan of
// triangles from each boundary edge to o, the centroid of the boundary vertices; those triangles add
// nothing to the sum, so the result is the volume of the mesh closed that way.
double enclosedVolume(const WorldMesh& mesh);

}  // namespace sixway::test
