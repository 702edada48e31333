#include "runtime/scene_lights.h"

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>
#include <stdexcept>
#include <variant>

namespace sixway::runtime {
namespace {

constexpr float kHuge = 1e30f;  // beyond it (or NaN) a value is not a light's

bool finite(glm::vec3 v) {
  return glm::all(glm::lessThan(glm::abs(v), glm::vec3(kHuge)));
}

}  // namespace

scene::Light sceneLight(const Light& light) {
  if (!finite(light.color) || !glm::all(glm::greaterThanEqual(light.color, glm::vec3(0.0f))) ||
      !(light.intensity >= 0.0f && light.intensity < kHuge))
    throw std::invalid_argument("Light: colour and intensity must be finite and non-negative");
  scene::Light l;
  if (light.kind == Light::Kind::Directional) {
    if (!finite(light.direction) || !(glm::length(light.direction) > 1e-6f))
      throw std::invalid_argument("Light: a directional light needs a direction");
    l.source = scene::DirectionalLight{glm::normalize(light.direction)};
  } else {
    if (!finite(light.position)) throw std::invalid_argument("Light: a point light needs a finite position");
    l.source = scene::PointLight{light.position};
  }
  l.color = light.color;
  l.intensity = light.intensity;
  l.shadows = light.shadows;
  return l;
}

Light publicLight(const scene::Light& light) {
  Light l;
  if (const auto* directional = std::get_if<scene::DirectionalLight>(&light.source)) {
    l.kind = Light::Kind::Directional;
    l.direction = directional->direction;
  } else {
    l.kind = Light::Kind::Point;
    l.position = std::get<scene::PointLight>(light.source).position;
  }
  l.color = light.color;
  l.intensity = light.intensity;
  l.shadows = light.shadows;
  return l;
}

}  // namespace sixway::runtime
