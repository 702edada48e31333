#include "scene_fixtures.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "cpu_lbm.h"

namespace sixway::test {
namespace {

// Σ of three modes sin(2π k·x/n + φ)/3 at cell centres, for one component.
std::vector<double> modes(glm::ivec3 size, std::mt19937& rng) {
  std::uniform_int_distribution<int> wave(-2, 2);
  std::uniform_real_distribution<double> phase(0, 2 * std::numbers::pi);
  std::vector<double> out(size_t(size.x) * size.y * size.z, 0.0);
  for (int m = 0; m < 3; ++m) {
    glm::ivec3 k(0);
    while (k == glm::ivec3(0)) k = {wave(rng), wave(rng), wave(rng)};
    const double phi = phase(rng);
    for (size_t c = 0; c < out.size(); ++c) {
      const glm::dvec3 x = (glm::dvec3(cellOf(int(c), size)) + 0.5) / glm::dvec3(size);
      out[c] += std::sin(2 * std::numbers::pi * glm::dot(glm::dvec3(k), x) + phi) / 3;
    }
  }
  return out;
}

}  // namespace

nlohmann::json latticeScene(glm::ivec3 size, double viscosity, const nlohmann::json& patch) {
  nlohmann::json scene = {
      {"grid", {{"size", {size.x, size.y, size.z}}, {"cell_size", 1.0}}},
      {"time", {{"frame_dt", 1.0}, {"steps_per_frame", 1}}},
      {"fluid", {{"viscosity", viscosity}, {"smagorinsky", 0.0}}},
      {"boundaries",
       {{"x-", "periodic"},
        {"x+", "periodic"},
        {"y-", "periodic"},
        {"y+", "periodic"},
        {"z-", "periodic"},
        {"z+", "periodic"}}},
      {"camera", {{"position", {0.0, 0.0, -50.0}}, {"target", {0.0, 0.0, 0.0}}}},
  };
  scene.merge_patch(patch);
  return scene;
}

scene::Scene parseLatticeScene(const nlohmann::json& scene) {
  return scene::parseScene(scene, "test-scene.json", ".");
}

std::vector<glm::vec3> smoothVelocity(glm::ivec3 size, float amplitude, uint32_t seed) {
  std::mt19937 rng(seed);
  const std::vector<double> x = modes(size, rng), y = modes(size, rng), z = modes(size, rng);
  std::vector<glm::vec3> out(x.size());
  for (size_t c = 0; c < out.size(); ++c) out[c] = amplitude * glm::vec3(x[c], y[c], z[c]);
  return out;
}

std::vector<float> smoothDensity(glm::ivec3 size, float amplitude, uint32_t seed) {
  std::mt19937 rng(seed);
  const std::vector<double> x = modes(size, rng);
  std::vector<float> out(x.size());
  for (size_t c = 0; c < out.size(); ++c) out[c] = float(1 + amplitude * x[c]);
  return out;
}

std::vector<glm::vec2> smoothSmoke(glm::ivec3 size, uint32_t seed) {
  std::mt19937 rng(seed);
  const std::vector<double> d = modes(size, rng), t = modes(size, rng);
  std::vector<glm::vec2> out(d.size());
  for (size_t c = 0; c < out.size(); ++c) out[c] = glm::vec2(1 + d[c], 0.5 + 0.5 * t[c]);
  return out;
}

std::vector<glm::dvec3> toDouble(const std::vector<glm::vec3>& v) {
  return {v.begin(), v.end()};
}
std::vector<double> toDouble(const std::vector<float>& v) {
  return {v.begin(), v.end()};
}
std::vector<glm::dvec2> toDouble(const std::vector<glm::vec2>& v) {
  return {v.begin(), v.end()};
}

std::string FieldError::where(glm::ivec3 size) const {
  if (cell < 0) return "no cell";
  const glm::ivec3 p = cellOf(cell, size);
  return "cell (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")";
}

FieldError maxDifference(const std::vector<glm::dvec4>& a, const std::vector<glm::dvec4>& b) {
  FieldError e;
  for (size_t c = 0; c < a.size(); ++c) {
    const glm::dvec4 d = glm::abs(a[c] - b[c]);
    const double worst = std::max({d.x, d.y, d.z, d.w});
    if (!(worst <= e.max)) {  // NaN counts as the worst
      e.max = std::isnan(worst) ? INFINITY : worst;
      e.cell = int(c);
    }
  }
  return e;
}

FieldError velocityError(const std::vector<glm::vec4>& gpu, const std::vector<glm::dvec4>& cpu) {
  std::vector<glm::dvec4> a(gpu.size()), b(cpu.size());
  for (size_t c = 0; c < a.size(); ++c) {
    a[c] = glm::dvec4(glm::dvec3(gpu[c]), 0);
    b[c] = glm::dvec4(glm::dvec3(cpu[c]), 0);
  }
  return maxDifference(a, b);
}

FieldError densityError(const std::vector<glm::vec4>& gpu, const std::vector<glm::dvec4>& cpu) {
  std::vector<glm::dvec4> a(gpu.size()), b(cpu.size());
  for (size_t c = 0; c < a.size(); ++c) {
    a[c] = glm::dvec4(0, 0, 0, gpu[c].w);
    b[c] = glm::dvec4(0, 0, 0, cpu[c].w);
  }
  return maxDifference(a, b);
}

}  // namespace sixway::test
