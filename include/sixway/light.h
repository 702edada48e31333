#pragma once
// A light of the engine's scene, as the six-way shading sees it (docs/conventions.md, "Shading"): each light
// blends the six lightmaps by its direction at the billboard, and obstacles shadow the smoke from it.
#include <glm/vec3.hpp>

namespace sixway {

struct Light {
  enum class Kind { Directional, Point };
  Kind kind = Kind::Directional;
  glm::vec3 direction{0.0f, 1.0f, 0.0f};  // directional: from the smoke toward the light (normalised here)
  glm::vec3 position{0.0f};               // point: world position (m)
  glm::vec3 color{1.0f};
  // Directional: irradiance (π lights a white lightmap texel to its value). Point: intensity I, the
  // irradiance at distance r being I / r².
  float intensity = 3.14159265f;
  bool shadows = true;  // obstacles cast shadows on the smoke from this light (a shadow-atlas tile each)
};

}  // namespace sixway
