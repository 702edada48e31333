#include "eval/obstacle_band.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <variant>

namespace sixway::eval {
namespace {

constexpr float kVisibleDepth = 4.6f;  // optical depth beyond which the smoke is hidden (1% transmittance)
constexpr float kCellAttenuation = 0.01f;  // σ_t·ρ·cell of a cell that counts as smoke

// Entry and exit distances of the ray through the box (entry >= exit: missed), from t = 0 on.
glm::vec2 rayBox(glm::vec3 o, glm::vec3 w, const render::Box& box) {
  glm::vec2 span(0.0f, 3.4e38f);
  for (int a = 0; a < 3; ++a) {
    if (std::abs(w[a]) < 1e-20f) {
      if (o[a] < box.min[a] || o[a] > box.max[a]) return {1.0f, 0.0f};
      continue;
    }
    float t0 = (box.min[a] - o[a]) / w[a], t1 = (box.max[a] - o[a]) / w[a];
    if (t0 > t1) std::swap(t0, t1);
    span = {std::max(span.x, t0), std::min(span.y, t1)};
  }
  return span;
}

// The density of the cell holding p (0 outside the grid).
float densityAt(const HostDensity& smoke, glm::vec3 p) {
  const glm::ivec3 cell(glm::floor((p - smoke.grid.origin) / smoke.grid.cellSize));
  const glm::ivec3 n = smoke.grid.size;
  if (glm::any(glm::lessThan(cell, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(cell, n))) return 0.0f;
  return smoke.values[(size_t(cell.z) * n.y + cell.y) * n.x + cell.x];
}

// Whether a shadow-casting obstacle lies between p and a shadow-casting light.
bool inShadow(const render::ObstacleBvh& obstacles, glm::vec3 p, const std::vector<scene::Light>& lights) {
  for (const scene::Light& light : lights) {
    if (!light.shadows) continue;
    glm::vec3 toLight;
    float distance = 3.4e38f;
    if (const auto* d = std::get_if<scene::DirectionalLight>(&light.source)) {
      toLight = glm::normalize(d->direction);
    } else {
      const glm::vec3 v = std::get<scene::PointLight>(light.source).position - p;
      distance = glm::length(v);
      toLight = v / distance;
    }
    if (obstacles.nearestHit(p, toLight, 0.0f, distance, true)) return true;
  }
  return false;
}

// Whether the ray meets visible smoke in an obstacle's shadow before `tEnd` (the obstacle it sees, if any).
bool seesShadowedSmoke(const render::ObstacleBvh& obstacles, glm::vec3 o, glm::vec3 w, float tEnd,
                       const std::vector<scene::Light>& lights, const HostDensity& smoke, float extinction) {
  const glm::vec2 span = rayBox(o, w, smoke.grid.bounds());
  const float step = 0.5f * smoke.grid.cellSize, end = std::min(span.y, tEnd);
  float depth = 0.0f;
  for (float t = span.x + 0.5f * step; t < end && depth < kVisibleDepth; t += step) {
    const glm::vec3 p = o + t * w;
    const float sigma = extinction * densityAt(smoke, p);
    depth += sigma * step;
    if (sigma * smoke.grid.cellSize >= kCellAttenuation && inShadow(obstacles, p, lights)) return true;
  }
  return false;
}

}  // namespace

int bandRadius(int height) {
  return std::max(2, int(std::lround(8.0 * height / 512.0)));
}

std::vector<uint8_t> obstacleBand(const render::ObstacleBvh& obstacles, const render::Camera& camera,
                                  const render::ImagePlane& plane, int width, int height,
                                  const std::vector<scene::Light>& lights, const HostDensity& smoke,
                                  const BandSettings& settings) {
  std::vector<uint8_t> band(size_t(width) * height, 0);
  std::vector<float> hit(size_t(width) * height, 3.4e38f);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const glm::vec3 w = render::rayDirection(camera, plane, {x + 0.5f, y + 0.5f}, width, height);
      if (const auto h = obstacles.nearestHit(camera.position, w, 0.0f, 3.4e38f))
        hit[size_t(y) * width + x] = h->t;
    }
  // The footprint grown by the radius (a disc around every covered pixel).
  const int r = settings.radius;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      if (hit[size_t(y) * width + x] == 3.4e38f) continue;
      for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
          const int u = x + dx, v = y + dy;
          if (dx * dx + dy * dy > r * r || u < 0 || v < 0 || u >= width || v >= height) continue;
          band[size_t(v) * width + u] = 1;
        }
    }
  if (!settings.shadows) return band;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t i = size_t(y) * width + x;
      if (band[i]) continue;
      const glm::vec3 w = render::rayDirection(camera, plane, {x + 0.5f, y + 0.5f}, width, height);
      band[i] = seesShadowedSmoke(obstacles, camera.position, w, hit[i], lights, smoke, settings.extinction);
    }
  return band;
}

}  // namespace sixway::eval
