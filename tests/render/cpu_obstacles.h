#pragma once
// CPU oracles for the obstacle passes (src/render/obstacle_pass.h, shadow_maps.h), in double precision and
// written from the definitions (docs/scene-format.md, docs/real-time-rendering.md), not from the shaders:
// camera rays, analytic ray intersections with spheres and boxes, ray–triangle tests against OBJ meshes
// placed as the scene format says, Lambertian shading, and depth-buffer conversions.
#include <functional>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <optional>
#include <vector>

#include "render/camera.h"
#include "scene/scene.h"

namespace sixway::test {

using glm::dvec3;

struct Ray {
  dvec3 origin, direction;  // direction unit
};

// The camera ray through (px, py) in pixel units (centres at x + 0.5) of a W × H image over `plane`.
Ray pixelRay(const render::Camera& camera, const render::ImagePlane& plane, double px, double py, int width,
             int height);

// Distance along the ray to its first surface point in front of the origin, if any.
std::optional<double> hitSphere(const Ray& ray, dvec3 centre, double radius);
std::optional<double> hitBox(const Ray& ray, dvec3 min, dvec3 max);

// World-space triangles of an OBJ mesh placed as docs/scene-format.md says: translate + Rz·Ry·Rx·(scale·p),
// with the rotation matrices written out here. The ray test bins the triangles by their projection into one
// camera's image, so that a ray through a pixel only tests the triangles over it.
class CpuMesh {
 public:
  CpuMesh(const scene::MeshObstacle& mesh);
  // Bins for rays through pixel coordinates of a W × H image over `plane`, up to `margin` pixels outside the
  // pixel of the ray (all triangles must lie in front of the camera).
  void bin(const render::Camera& camera, const render::ImagePlane& plane, int width, int height, int margin);
  // Nearest hit of the binned camera's ray through pixel coordinate (px, py).
  std::optional<double> hitPixel(double px, double py) const;

 private:
  std::vector<dvec3> corners_;  // three per triangle
  render::Camera camera_;
  render::ImagePlane plane_;
  int width_ = 0, height_ = 0, margin_ = 0;
  std::vector<std::vector<unsigned>> bins_;  // per pixel of the image grown by the margin
};

// Möller–Trumbore, both sides.
std::optional<double> hitTriangle(const Ray& ray, dvec3 a, dvec3 b, dvec3 c);

// Whether the analytic coverage changes within one pixel of pixel (x, y): `covered(px, py)` at the pixel's
// centre differs from its value at one of the eight points one pixel away (the rasterizer and the analytic
// shape may then disagree by the tessellation and the sampling position).
bool nearSilhouette(const std::function<bool(double, double)>& covered, int x, int y);

// View depth (along camera.forward) of a depth-buffer value of render::projectionMatrix(plane, {near, far}):
// the inverse of d = far (z − near) / (z (far − near)).
double viewDepthFromDepthBuffer(double d, double near, double far);

// Outgoing radiance of a Lambertian surface with albedo `albedo` at `p`, unit normal `n`, under the lights
// (directional: irradiance = intensity·colour·max(0, n·l); point: intensity·colour·max(0, n·l)/r²) and the
// ambient radiance max(0, L0 + L1·w), whose cosine-weighted hemisphere integral is π·(L0 + (2/3) L1·n).
dvec3 lambert(dvec3 albedo, dvec3 p, dvec3 n, const std::vector<scene::Light>& lights,
              const std::optional<scene::Ambient>& ambient);

// Position of a keyframed motion at `seconds` (linear between keyframes, held at the ends; no loop).
dvec3 keyframePosition(const scene::Motion& motion, double seconds);

// The clip-space point of `p` under `m` after the perspective divide.
dvec3 project(const glm::mat4& m, dvec3 p);
// The world points that `m` maps to ndc (x, y, 0) and (x, y, 1).
std::pair<dvec3, dvec3> unproject(const glm::mat4& m, double ndcX, double ndcY);

}  // namespace sixway::test
