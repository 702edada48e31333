#include "render/scene_frame.h"

#include <algorithm>
#include <glm/gtc/quaternion.hpp>
#include <glm/trigonometric.hpp>
#include <variant>

namespace sixway::render {

Camera sceneCamera(const scene::Camera& camera, int frame) {
  glm::vec3 position = camera.position;
  if (camera.path) {
    if (const auto* orbit = std::get_if<scene::CameraOrbit>(&*camera.path)) {
      const float angle = glm::radians(orbit->degreesPerFrame * float(frame));
      position = camera.target + glm::angleAxis(angle, camera.up) * (camera.position - camera.target);
    } else {
      const auto& dolly = std::get<scene::CameraDolly>(*camera.path);
      const float s = std::min(1.0f, float(frame) / float(dolly.frames));
      position = camera.position + s * (dolly.endPosition - camera.position);
    }
  }
  return Camera::lookAt(position, camera.target, camera.up, camera.fovDeg);
}

std::vector<scene::Light> sceneLights(const std::vector<scene::Light>& lights, int frame) {
  std::vector<scene::Light> moved = lights;
  for (scene::Light& light : moved) {
    if (!light.path) continue;
    const glm::quat turn =
        glm::angleAxis(glm::radians(light.path->degreesPerFrame * float(frame)), light.path->axis);
    if (auto* directional = std::get_if<scene::DirectionalLight>(&light.source)) {
      directional->direction = turn * directional->direction;
    } else {
      auto& point = std::get<scene::PointLight>(light.source);
      point.position = light.path->center + turn * (point.position - light.path->center);
    }
    light.path.reset();
  }
  return moved;
}

}  // namespace sixway::render
