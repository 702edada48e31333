#include "render/projection.h"

#include <algorithm>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

#include "render/camera_error.h"
#include "render/volume.h"

namespace sixway::render {

glm::mat4 viewMatrix(const Camera& camera) {
  return glm::lookAtRH(camera.position, camera.position + camera.forward, camera.up);
}

glm::mat4 projectionMatrix(const ImagePlane& plane, DepthRange depth) {
  // glm::frustumRH_ZO takes the rectangle on the near plane; ours is at distance 1.
  return glm::frustumRH_ZO(plane.min.x * depth.near, plane.max.x * depth.near, plane.min.y * depth.near,
                           plane.max.y * depth.near, depth.near, depth.far);
}

DepthMapping depthMapping(DepthRange range) {
  const double near = range.near, far = range.far;
  return {far / (far - near), -near * far / (far - near)};
}

DepthRange boxDepthRange(const Camera& camera, const Box& box, float margin, float minNear) {
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                      (corner & 4) ? box.max.z : box.min.z);
    const float z = glm::dot(p - camera.position, camera.forward);
    lo = std::min(lo, z);
    hi = std::max(hi, z);
  }
  if (hi <= minNear) throw CameraError("the volume is behind the camera");
  const float pad = margin * (hi - lo);
  return {std::max(lo - pad, minNear), hi + pad};
}

}  // namespace sixway::render
