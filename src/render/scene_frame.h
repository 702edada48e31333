#pragma once
// The scene's camera and lights at a given frame, their paths applied (docs/scene-format.md).
#include <vector>

#include "io/scene.h"
#include "render/camera.h"

namespace sixway::render {

// The camera moved along its orbit or dolly path to frame `frame`.
Camera sceneCamera(const io::Camera& camera, int frame);

// The lights turned along their orbits to frame `frame` (a point light's position about its orbit line, a
// directional light's direction about the orbit axis).
std::vector<io::Light> sceneLights(const std::vector<io::Light>& lights, int frame);

}  // namespace sixway::render
