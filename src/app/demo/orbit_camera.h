#pragma once
// The demo's camera: it orbits a target point (yaw about +y, pitch above the horizon), zooms toward it and
// pans it across the view, the way model viewers move.
#include <sixway/smoke_renderer.h>

#include <glm/vec3.hpp>

#include "render/camera.h"
#include "scene/scene.h"

namespace sixway::app::demo {

struct OrbitCamera {
  glm::vec3 target{0.0f};
  float distance = 1.0f;
  float yawDeg = 0.0f;    // about +y; 0 looks along −z
  float pitchDeg = 0.0f;  // above the horizon, within ±89°
  float fovDeg = 40.0f;

  // The scene's camera at its start (its path is not followed: the user moves the camera).
  static OrbitCamera fromScene(const scene::Camera& camera);
  glm::vec3 position() const;
  render::Camera camera() const;
  // The same, as the public API's camera.
  Camera view() const;

  void orbit(float yawDegrees, float pitchDegrees);
  // Multiplies the distance to the target (factor > 0).
  void zoom(float factor);
  // Moves the target across the view by (right, up) fractions of the distance.
  void pan(float right, float up);
};

}  // namespace sixway::app::demo
