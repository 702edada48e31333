#pragma once
// The scene's camera and lights at a given frame, their paths applied (docs/scene-format.md).
#include <vector>

#include "render/camera.h"
#include "scene/scene.h"

namespace sixway::render {

// The camera moved along its orbit or dolly path to frame `frame`.
Camera sceneCamera(const scene::Camera& camera, int frame);

// The lights turned along their orbits to frame `frame` (a point light's position about its orbit line, a
// directional light's direction about the orbit axis).
std::vector<scene::Light> sceneLights(const std::vector<scene::Light>& lights, int frame);

}  // namespace sixway::render
