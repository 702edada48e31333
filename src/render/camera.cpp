#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <stdexcept>

#include "render/volume.h"

namespace sixway::render {

Camera Camera::lookAt(glm::vec3 position, glm::vec3 target, glm::vec3 up, float fovYDeg) {
  const glm::vec3 view = target - position;
  if (glm::length(view) <= 0.0f) throw std::invalid_argument("camera: target equals position");
  Camera c;
  c.position = position;
  c.forward = glm::normalize(view);
  const glm::vec3 side = glm::cross(c.forward, up);
  if (glm::length(side) < 1e-6f * glm::length(up))
    throw std::invalid_argument("camera: up is parallel to the view");
  c.right = glm::normalize(side);
  c.up = glm::cross(c.right, c.forward);
  c.fovYDeg = fovYDeg;
  return c;
}

Camera framingCamera(const Box& box, float fovYDeg) {
  const float radius = 0.5f * glm::length(box.size());
  const float distance = std::max(radius, 1e-6f) / std::sin(0.5f * glm::radians(fovYDeg));
  const glm::vec3 centre = box.centre();
  return Camera::lookAt(centre + glm::vec3(0.0f, 0.0f, distance), centre, {0.0f, 1.0f, 0.0f}, fovYDeg);
}

ImagePlane fullFrame(const Camera& camera, int width, int height) {
  const float tanY = std::tan(0.5f * glm::radians(camera.fovYDeg));
  const float tanX = tanY * float(width) / float(height);
  return {{-tanX, -tanY}, {tanX, tanY}};
}

glm::vec3 rayDirection(const Camera& camera, const ImagePlane& plane, glm::vec2 pixel, int width,
                       int height) {
  const glm::vec2 uv = pixel / glm::vec2(width, height);
  const glm::vec2 q(plane.min.x + uv.x * (plane.max.x - plane.min.x),
                    plane.max.y + uv.y * (plane.min.y - plane.max.y));
  return glm::normalize(camera.forward + q.x * camera.right + q.y * camera.up);
}

}  // namespace sixway::render
