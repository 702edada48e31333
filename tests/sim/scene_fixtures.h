#pragma once
// Scenes in lattice units and smooth initial fields for the simulation tests, and the comparison of a
// GPU field with its CPU reference.
#include <cstdint>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace sixway::test {

// A scene in lattice units: cells of 1 m from the origin, one lattice step per frame of 1 s (so m/s are
// cells per step and m/s² cells per step²), every face periodic, viscosity ν (τ = 3ν + ½), no turbulence
// model; `patch` merged in (RFC 7386: objects merge, arrays and values replace).
nlohmann::json latticeScene(glm::ivec3 size, double viscosity,
                            const nlohmann::json& patch = nlohmann::json::object());
scene::Scene parseLatticeScene(const nlohmann::json& scene);

// Smooth fields: three Fourier modes per component with random wave vectors and phases, periodic in
// the box, |value − mean| ≤ amplitude.
std::vector<glm::vec3> smoothVelocity(glm::ivec3 size, float amplitude, uint32_t seed);
std::vector<float> smoothDensity(glm::ivec3 size, float amplitude, uint32_t seed);  // around 1
// (density, temperature) in [0, 2] and [0, 1], smooth.
std::vector<glm::vec2> smoothSmoke(glm::ivec3 size, uint32_t seed);

std::vector<glm::dvec3> toDouble(const std::vector<glm::vec3>& v);
std::vector<double> toDouble(const std::vector<float>& v);
std::vector<glm::dvec2> toDouble(const std::vector<glm::vec2>& v);

// The largest |gpu − cpu| over the cells, and where.
struct FieldError {
  double max = 0;
  int cell = -1;
  std::string where(glm::ivec3 size) const;  // "cell (i, j, k)"
};
FieldError velocityError(const std::vector<glm::vec4>& gpu, const std::vector<glm::dvec4>& cpu);
FieldError densityError(const std::vector<glm::vec4>& gpu, const std::vector<glm::dvec4>& cpu);
FieldError maxDifference(const std::vector<glm::dvec4>& a, const std::vector<glm::dvec4>& b);

}  // namespace sixway::test
