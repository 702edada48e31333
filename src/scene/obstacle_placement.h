#pragma once
// Where a scene's obstacle is (scene::Obstacle, docs/scene-format.md): its keyframed motion at a time and a
// mesh's rotation. The simulation voxelizes the obstacle there and the renderers draw it there, so both read
// it from here.
#include <glm/glm.hpp>

#include "io/obj.h"
#include "scene/scene.h"

namespace sixway::scene {

// Position and velocity of a keyframed motion at time t (linear between keyframes, held at the
// ends or repeated with `loop`).
struct MotionState {
  glm::vec3 position;
  glm::vec3 velocity;
};
MotionState evaluateMotion(const Motion& motion, double seconds);

// The rotation of a mesh obstacle, R = Rz·Ry·Rx of rotate_deg (x applied first), or the one it holds:
// world = translate + R·(scale·p).
glm::mat3 meshRotation(const MeshObstacle& mesh);
// A mesh obstacle's triangles: those it holds, or its file's (io::readObj, whose InputError names it).
io::Mesh meshTriangles(const MeshObstacle& mesh);

}  // namespace sixway::scene
