#include "support/scene_parts.h"

#include <glm/geometric.hpp>

namespace sixway::test {

scene::Obstacle sphereAt(glm::vec3 centre, float radius, bool shadows) {
  scene::Obstacle o;
  o.shape = scene::SphereObstacle{centre, radius};
  o.shadows = shadows;
  return o;
}

scene::Light directionalLight(glm::vec3 towardLight, float intensity, bool shadows, glm::vec3 color) {
  scene::Light l;
  l.source = scene::DirectionalLight{glm::normalize(towardLight)};
  l.intensity = intensity;
  l.shadows = shadows;
  l.color = color;
  return l;
}

}  // namespace sixway::test
