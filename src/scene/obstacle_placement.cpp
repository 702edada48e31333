#include "scene/obstacle_placement.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace sixway::scene {

MotionState evaluateMotion(const Motion& motion, double seconds) {
  const auto& keys = motion.keyframes;
  const double first = keys.front().time, last = keys.back().time;
  if (motion.loop)
    seconds = first + std::fmod(std::fmod(seconds - first, last - first) + (last - first), last - first);
  if (seconds < first) return {keys.front().position, glm::vec3(0)};
  if (seconds >= last) return {keys.back().position, glm::vec3(0)};
  // The segment [t_k, t_k+1) holding the time: at a keyframe, the one the coming step moves along.
  size_t k = 0;
  while (keys[k + 1].time <= seconds) ++k;
  const float span = keys[k + 1].time - keys[k].time;
  const float t = float(seconds - keys[k].time) / span;
  return {glm::mix(keys[k].position, keys[k + 1].position, t),
          (keys[k + 1].position - keys[k].position) / span};
}

glm::mat3 meshRotation(const MeshObstacle& mesh) {
  if (mesh.rotation) return *mesh.rotation;
  glm::mat4 r(1.0f);
  r = glm::rotate(r, glm::radians(mesh.rotateDeg.z), glm::vec3(0, 0, 1));
  r = glm::rotate(r, glm::radians(mesh.rotateDeg.y), glm::vec3(0, 1, 0));
  r = glm::rotate(r, glm::radians(mesh.rotateDeg.x), glm::vec3(1, 0, 0));
  return glm::mat3(r);
}

io::Mesh meshTriangles(const MeshObstacle& mesh) {
  return mesh.data ? *mesh.data : io::readObj(mesh.file);
}

}  // namespace sixway::scene
