#pragma once
// The public sixway::Light and the scene's scene::Light, one into the other (a public light has no path: an
// engine moves its lights itself).
#include <sixway/light.h>

#include "scene/scene.h"

namespace sixway::runtime {

// std::invalid_argument for a negative or non-finite colour or intensity, a directional light without a
// direction, or a point light without a finite position.
scene::Light sceneLight(const Light& light);
// The light as it is now (its path, if any, is dropped).
Light publicLight(const scene::Light& light);

}  // namespace sixway::runtime
