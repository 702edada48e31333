#include "app/demo/orbit_camera.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace sixway::app::demo {

OrbitCamera OrbitCamera::fromScene(const scene::Camera& camera) {
  OrbitCamera c;
  const glm::vec3 offset = camera.position - camera.target;
  c.target = camera.target;
  c.distance = std::max(glm::length(offset), 1e-3f);
  c.yawDeg = glm::degrees(std::atan2(offset.x, offset.z));
  c.pitchDeg =
      std::clamp(glm::degrees(std::asin(std::clamp(offset.y / c.distance, -1.0f, 1.0f))), -89.0f, 89.0f);
  c.fovDeg = camera.fovDeg;
  return c;
}

glm::vec3 OrbitCamera::position() const {
  const float yaw = glm::radians(yawDeg), pitch = glm::radians(pitchDeg);
  return target + distance * glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                       std::cos(pitch) * std::cos(yaw));
}

render::Camera OrbitCamera::camera() const {
  return render::Camera::lookAt(position(), target, glm::vec3(0.0f, 1.0f, 0.0f), fovDeg);
}

Camera OrbitCamera::view() const {
  Camera c;
  c.position = position();
  c.target = target;
  c.up = glm::vec3(0.0f, 1.0f, 0.0f);
  c.fovYDegrees = fovDeg;
  return c;
}

void OrbitCamera::orbit(float yawDegrees, float pitchDegrees) {
  yawDeg = std::fmod(yawDeg + yawDegrees, 360.0f);
  pitchDeg = std::clamp(pitchDeg + pitchDegrees, -89.0f, 89.0f);
}

void OrbitCamera::zoom(float factor) {
  if (factor > 0.0f) distance = std::clamp(distance * factor, 1e-2f, 1e3f);
}

void OrbitCamera::pan(float right, float up) {
  const render::Camera c = camera();
  target += distance * (right * c.right + up * c.up);
}

}  // namespace sixway::app::demo
