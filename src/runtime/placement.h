#pragma once
// A smoke instance's placement in the engine's world (SmokeSimulation::setPlacement): world = placement ·
// scene, upright (a rotation about y and a translation), and what crosses between the two spaces: the
// engine's camera and lights into the scene, the lightmaps' corners out to the world.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace sixway::runtime {

// `worldFromScene` checked upright and rigid (columns to 1e-4) and returned with its rotation made exact;
// std::invalid_argument otherwise.
glm::mat4 uprightPlacement(const glm::mat4& worldFromScene);

glm::vec3 scenePoint(const glm::mat4& worldFromScene, glm::vec3 world);
glm::vec3 sceneDirection(const glm::mat4& worldFromScene, glm::vec3 world);
glm::vec3 worldPoint(const glm::mat4& worldFromScene, glm::vec3 scene);

}  // namespace sixway::runtime
