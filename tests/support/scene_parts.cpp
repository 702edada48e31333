#include "support/scene_parts.h"

#include <glm/geometric.hpp>

namespace sixway::test {

io::Obstacle sphereAt(glm::vec3 centre, float radius, bool shadows) {
  io::Obstacle o;
  o.shape = io::SphereObstacle{centre, radius};
  o.shadows = shadows;
  return o;
}

io::Light directionalLight(glm::vec3 towardLight, float intensity, bool shadows, glm::vec3 color) {
  io::Light l;
  l.source = io::DirectionalLight{glm::normalize(towardLight)};
  l.intensity = intensity;
  l.shadows = shadows;
  l.color = color;
  return l;
}

}  // namespace sixway::test
