#include "render/engine_view.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/trigonometric.hpp>
#include <stdexcept>

namespace sixway::render {
namespace {

bool near0(float value, float scale) {
  return std::abs(value) <= 1e-5f * scale;
}

void requireRigid(const glm::mat4& view) {
  const glm::mat3 r(view);
  const glm::mat3 gram = glm::transpose(r) * r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (std::abs(gram[i][j] - (i == j ? 1.0f : 0.0f)) > 1e-4f)
        throw std::invalid_argument("engine view: the view matrix is not a rotation and a translation");
  if (!near0(view[0][3], 1) || !near0(view[1][3], 1) || !near0(view[2][3], 1) || !near0(view[3][3] - 1.0f, 1))
    throw std::invalid_argument("engine view: the view matrix has a projective row");
}

}  // namespace

EngineView engineView(const glm::mat4& view, const glm::mat4& projection) {
  requireRigid(view);
  // glm is column-major: p[c][r] multiplies coordinate c into clip row r. Clip w must be ±z_view (scaled).
  const float wScale = projection[2][3];
  if (wScale == 0.0f || !near0(projection[0][3], std::abs(wScale)) ||
      !near0(projection[1][3], std::abs(wScale)) || !near0(projection[3][3], std::abs(wScale)))
    throw std::invalid_argument("engine view: the projection is not a perspective (clip w must be ±z_view)");
  const glm::mat4 p = projection / std::abs(wScale);
  const float s = wScale > 0.0f ? 1.0f : -1.0f;  // w = s z_view: s = −1 right-handed, +1 left-handed
  const float xyScale = std::max(std::abs(p[0][0]), std::abs(p[1][1]));
  if (p[0][0] == 0.0f || p[1][1] == 0.0f || p[3][2] == 0.0f)
    throw std::invalid_argument("engine view: the projection is singular");
  if (!near0(p[1][0], xyScale) || !near0(p[0][1], xyScale) || !near0(p[3][0], xyScale) ||
      !near0(p[3][1], xyScale) || !near0(p[0][2], xyScale) || !near0(p[1][2], xyScale))
    throw std::invalid_argument(
        "engine view: the projection skews, or offsets the image by depth (only the z column may shift it)");

  // The view's axes in the world (rows of the rotation) and its origin.
  const glm::mat3 toView(view);
  const glm::mat3 axes = glm::transpose(toView);
  EngineView result;
  Camera& c = result.camera;
  c.position = -(axes * glm::vec3(view[3]));
  c.forward = s * axes[2];
  c.up = axes[1];
  c.right = glm::cross(c.forward, c.up);  // the frame's convention (Camera::lookAt), whatever the view's
  const float handed = glm::dot(c.right, axes[0]) > 0.0f ? 1.0f : -1.0f;

  // A point at view depth 1 (w = 1) on the image plane q: x_ndc = handed p00 q.x + s p20,
  // y_ndc = p11 q.y + s p21. A left-handed view (or a mirroring world transform) in sixway's right-handed
  // world is a mirror camera: its plane runs right to left (min.x > max.x), and the shading draws it so.
  const float left = (-1.0f - s * p[2][0]) / (handed * p[0][0]);
  const float right = (1.0f - s * p[2][0]) / (handed * p[0][0]);
  const float top = (-1.0f - s * p[2][1]) / p[1][1];
  const float bottom = (1.0f - s * p[2][1]) / p[1][1];
  if (top <= bottom)
    throw std::invalid_argument(
        "engine view: NDC y = -1 is the bottom row (a projection for a negative-height viewport): negate its "
        "second row");
  result.plane = {{left, bottom}, {right, top}};
  c.fovYDeg = glm::degrees(2.0f * std::atan(0.5f * (top - bottom)));
  // d = (p22 z + p32) / w with z = s w: d = s p22 + p32 / w.
  result.depth = {double(s * p[2][2]), double(p[3][2])};
  return result;
}

}  // namespace sixway::render
