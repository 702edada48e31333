#pragma once
// Scene parts the tests build again and again: a sphere obstacle, a directional light.
#include <glm/vec3.hpp>

#include "scene/scene.h"

namespace sixway::test {

// A sphere obstacle (casting shadows unless told not to).
scene::Obstacle sphereAt(glm::vec3 centre, float radius, bool shadows = true);

// A directional light toward `towardLight` (normalised here) of irradiance `intensity`.
scene::Light directionalLight(glm::vec3 towardLight, float intensity, bool shadows = true,
                              glm::vec3 color = glm::vec3(1.0f));

}  // namespace sixway::test
