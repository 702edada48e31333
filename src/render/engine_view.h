#pragma once
// An engine's camera as its shaders have it, a view and a projection matrix, in the terms the real-time
// frame works in: the camera's position and axes, the rectangle of the image plane its target covers (TAA
// jitter and off-centre frusta included) and how its depth buffer maps to view depth (standard, reversed-Z,
// infinite far plane). docs/embedding.md, "The camera".
#include <glm/mat4x4.hpp>

#include "render/camera.h"
#include "render/projection.h"

namespace sixway::render {

struct EngineView {
  Camera camera;
  ImagePlane plane;    // what the target covers, row 0 at the top; min.x > max.x for a mirror camera
  DepthMapping depth;  // what the target's depth buffer holds
};

// `view`: world → view space, rigid (right- or left-handed). `projection`: a perspective projection into
// Vulkan's clip space with w the view depth (w = ±z_view), no skew, drawn with a viewport of positive height
// (NDC y = −1 at the top row of the target), depth any map d = a + b / w. Throws std::invalid_argument for a
// view that is not rigid, a projection that is not such a perspective, or one for a negative-height viewport.
EngineView engineView(const glm::mat4& view, const glm::mat4& projection);

}  // namespace sixway::render
