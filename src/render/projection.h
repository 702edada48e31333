#pragma once
// Rasterization matrices of a camera, shared by every graphics pass of the real-time renderer (obstacles,
// shadow maps, the smoke billboard) and by the compute passes that compare against their depth buffers.
// Clip space is Vulkan's with depth 0..1; gpu::Sequence::render uses a negative-height viewport, so NDC y
// points up (row 0 of the image is the top), matching ImagePlane and shaders/common/camera.glsl.
#include <glm/mat4x4.hpp>

#include "render/camera.h"

namespace sixway::render {

struct Box;

// Near and far planes of a perspective projection, in view depth (distance along camera.forward).
struct DepthRange {
  float near = 0.01f, far = 100.0f;
};

// What a depth buffer holds at view depth v: d = offset + scale / v. Every perspective projection into
// Vulkan's clip space has this form: projectionMatrix's (0 at near, 1 at far), reversed-Z (1 at near, 0 at
// far) and an infinite far plane (offset 0 reversed, 1 standard). shaders/common/depth.glsl inverts it.
struct DepthMapping {
  double offset = 0.0,
         scale = 0.0;  // double: the shading takes the offset's float rounding apart (depth.glsl)
};

// projectionMatrix's depth: offset far / (far − near), scale −near far / (far − near).
DepthMapping depthMapping(DepthRange range);

// World → camera view space (x right, y up, −z forward).
glm::mat4 viewMatrix(const Camera& camera);

// The perspective projection whose frustum is exactly `plane` (a rectangle of the image plane at distance 1,
// e.g. fullFrame() or a billboard) between `depth.near` and `depth.far`; depth 0 at near, 1 at far.
glm::mat4 projectionMatrix(const ImagePlane& plane, DepthRange depth);

// The view depths spanned by the box's corners, widened by `margin` (a fraction of the span) on both sides
// and with near kept ≥ `minNear`. Throws io::InputError (source "camera") when the whole box is behind the
// camera.
DepthRange boxDepthRange(const Camera& camera, const Box& box, float margin = 0.01f, float minNear = 1e-3f);

}  // namespace sixway::render
