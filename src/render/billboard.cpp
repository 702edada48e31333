#include "render/billboard.h"

#include <algorithm>
#include <glm/geometric.hpp>
#include <limits>

#include "render/camera_error.h"

namespace sixway::render {

ImagePlane billboardBounds(const Camera& camera, const Box& box, float aspect) {
  ImagePlane r{glm::vec2(std::numeric_limits<float>::max()), glm::vec2(std::numeric_limits<float>::lowest())};
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                      (corner & 4) ? box.max.z : box.min.z);
    const glm::vec3 q = p - camera.position;
    const float depth = glm::dot(q, camera.forward);
    if (depth <= 1e-4f * glm::length(q))
      throw CameraError("the volume's box reaches behind the camera; move the camera away from it");
    const glm::vec2 projected(glm::dot(q, camera.right) / depth, glm::dot(q, camera.up) / depth);
    r.min = glm::min(r.min, projected);
    r.max = glm::max(r.max, projected);
  }
  if (aspect > 0.0f) {
    const glm::vec2 centre = 0.5f * (r.min + r.max);
    glm::vec2 half = 0.5f * (r.max - r.min);
    if (half.x < aspect * half.y) {
      half.x = aspect * half.y;
    } else {
      half.y = half.x / aspect;
    }
    r = {centre - half, centre + half};
  }
  return r;
}

std::array<glm::vec3, 4> billboardCorners(const Camera& camera, const ImagePlane& billboard, float depth) {
  auto at = [&](float x, float y) {
    return camera.position + depth * (camera.forward + x * camera.right + y * camera.up);
  };
  return {at(billboard.min.x, billboard.min.y), at(billboard.max.x, billboard.min.y),
          at(billboard.max.x, billboard.max.y), at(billboard.min.x, billboard.max.y)};
}

}  // namespace sixway::render
