#pragma once
// Evaluating the keyframed motion of a scene's obstacle (io::Motion, docs/scene-format.md): the simulation
// voxelizes the obstacle there and the renderers draw it there, so both read it from here.
#include <glm/glm.hpp>

#include "io/scene.h"

namespace sixway::io {

// Position and velocity of a keyframed motion at time t (linear between keyframes, held at the
// ends or repeated with `loop`).
struct MotionState {
  glm::vec3 position;
  glm::vec3 velocity;
};
MotionState evaluateMotion(const Motion& motion, double seconds);

}  // namespace sixway::io
