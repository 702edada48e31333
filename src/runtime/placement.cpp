#include "runtime/placement.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <stdexcept>

namespace sixway::runtime {

glm::mat4 uprightPlacement(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) throw std::invalid_argument("SmokeSimulation::setPlacement: not finite");
  constexpr float kTolerance = 1e-4f;
  const glm::vec3 x(m[0]), y(m[1]), z(m[2]);
  const bool affine = m[0][3] == 0.0f && m[1][3] == 0.0f && m[2][3] == 0.0f && m[3][3] == 1.0f;
  const bool upright = glm::length(y - glm::vec3(0.0f, 1.0f, 0.0f)) < kTolerance &&
                       std::abs(x.y) < kTolerance && std::abs(z.y) < kTolerance;
  const bool rotation = std::abs(glm::length(x) - 1.0f) < kTolerance &&
                        std::abs(glm::dot(x, z)) < kTolerance &&
                        glm::length(glm::cross(x, glm::vec3(0.0f, 1.0f, 0.0f)) - z) < kTolerance;
  if (!affine || !upright || !rotation)
    throw std::invalid_argument(
        "SmokeSimulation::setPlacement: needs a rotation about the y axis and a translation (the smoke rises "
        "along y; no tilt, scale or mirror)");
  // The rotation from its angle, so that the inverse is exact.
  const float angle = std::atan2(-x.z, x.x);
  const float c = std::cos(angle), s = std::sin(angle);
  glm::mat4 exact(1.0f);
  exact[0] = glm::vec4(c, 0.0f, -s, 0.0f);
  exact[2] = glm::vec4(s, 0.0f, c, 0.0f);
  exact[3] = m[3];
  return exact;
}

glm::vec3 scenePoint(const glm::mat4& worldFromScene, glm::vec3 world) {
  return glm::vec3(glm::inverse(worldFromScene) * glm::vec4(world, 1.0f));
}

glm::vec3 sceneDirection(const glm::mat4& worldFromScene, glm::vec3 world) {
  return glm::vec3(glm::inverse(worldFromScene) * glm::vec4(world, 0.0f));
}

glm::vec3 worldPoint(const glm::mat4& worldFromScene, glm::vec3 scene) {
  return glm::vec3(worldFromScene * glm::vec4(scene, 1.0f));
}

}  // namespace sixway::runtime
