#pragma once
// The billboard of a volume: the rectangle of the camera's image plane that holds the projection of the
// volume's box. The six-way lightmaps of a frame cover exactly this rectangle, and the real-time renderer
// draws its camera-facing quad over it.
#include <array>
#include <glm/vec3.hpp>

#include "render/camera.h"
#include "render/volume.h"

namespace sixway::render {

// The smallest rectangle holding the projections of the box's eight corners, widened symmetrically (in x or
// in y) to the aspect ratio `aspect` = width / height of the lightmap, so that its texels are square; with
// aspect 0 it stays tight. Throws io::InputError (source "camera") when a corner lies behind the camera.
ImagePlane billboardBounds(const Camera& camera, const Box& box, float aspect = 0.0f);

// The world-space corners of the billboard rectangle at distance `depth` along the view axis, in the order
// bottom-left, bottom-right, top-right, top-left.
std::array<glm::vec3, 4> billboardCorners(const Camera& camera, const ImagePlane& billboard, float depth);

}  // namespace sixway::render
