#pragma once
// Pinhole cameras and the rectangles of their image plane that images cover. Shared by the reference
// renderers and the real-time renderer; the GPU side is shaders/common/camera.glsl.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace sixway::render {

struct Box;

// Position and orthonormal axes in world space (right-handed: right × up = −forward).
struct Camera {
  glm::vec3 position{0.0f, 0.0f, 1.0f};
  glm::vec3 right{1.0f, 0.0f, 0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};
  float fovYDeg = 40.0f;  // vertical field of view of a whole frame

  // Throws std::invalid_argument when target = position or up is parallel to the view.
  static Camera lookAt(glm::vec3 position, glm::vec3 target, glm::vec3 up, float fovYDeg);
};

// The default view of a volume: from +z looking −z (up = +y), at the distance where the box's bounding
// sphere just fits the vertical field of view.
Camera framingCamera(const Box& box, float fovYDeg = 40.0f);

// A rectangle of the image plane at distance 1 in front of the camera (x right, y up). An image of
// W × H pixels covering it puts the centre of pixel (x, y) at
//   (mix(min.x, max.x, (x + 0.5) / W), mix(max.y, min.y, (y + 0.5) / H))      (row 0 at the top)
// and its ray through position + forward + p.x · right + p.y · up.
struct ImagePlane {
  glm::vec2 min{-1.0f}, max{1.0f};
};

// The camera's whole view for a W × H image with square pixels.
ImagePlane fullFrame(const Camera& camera, int width, int height);

// The direction of the ray through pixel coordinate `pixel` (pixel centres at x + 0.5, y + 0.5).
glm::vec3 rayDirection(const Camera& camera, const ImagePlane& plane, glm::vec2 pixel, int width, int height);

}  // namespace sixway::render
