#include "app/bench_scene.h"

#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <variant>

#include "io/error.h"

namespace sixway::app {
namespace {

// A hash of a lattice point to [0, 1): the seeded corners of the value noise.
float hashToUnit(glm::ivec3 p) {
  uint32_t h = uint32_t(p.x) * 73856093u ^ uint32_t(p.y) * 19349663u ^ uint32_t(p.z) * 83492791u;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return float(h & 0xffffffu) / float(0x1000000);
}

// Trilinear value noise with smoothstep weights, in [0, 1).
float valueNoise(glm::vec3 p) {
  const glm::vec3 floorP = glm::floor(p);
  const glm::ivec3 cell(floorP);
  const glm::vec3 f = p - floorP;
  const glm::vec3 w = f * f * (3.0f - 2.0f * f);
  float value = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::ivec3 o(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    const float weight = (o.x ? w.x : 1 - w.x) * (o.y ? w.y : 1 - w.y) * (o.z ? w.z : 1 - w.z);
    value += weight * hashToUnit(cell + o);
  }
  return value;
}

}  // namespace

scene::Scene benchScene(const std::filesystem::path& file, glm::ivec3 lattice) {
  scene::Scene scene = scene::loadScene(file);
  scene::requireSimulated(scene, file.string());
  if (scene.inlets.empty()) throw io::InputError(file.string(), "the bench scene needs an inlet");
  scene.grid.cellSize *= float(scene.grid.size.x) / float(lattice.x);
  scene.grid.size = lattice;
  return scene;
}

std::vector<glm::vec2> benchSmoke(const scene::Scene& scene) {
  const glm::ivec3 size = scene.grid.size * scene.grid.smokeUpres;
  const float dx = scene.grid.cellSize / float(scene.grid.smokeUpres);
  const glm::vec3 extent = glm::vec3(scene.grid.size) * scene.grid.cellSize;
  const scene::Inlet& inlet = scene.inlets.front();
  const glm::vec3 source =
      std::holds_alternative<scene::InletDisk>(inlet.shape)
          ? std::get<scene::InletDisk>(inlet.shape).center
          : 0.5f * (std::get<scene::InletBox>(inlet.shape).min + std::get<scene::InletBox>(inlet.shape).max);
  const float height = 0.7f * extent.y;  // the column's top, above the source
  std::vector<glm::vec2> smoke(size_t(size.x) * size.y * size.z, glm::vec2(0));
  for (int k = 0; k < size.z; ++k)
    for (int j = 0; j < size.y; ++j)
      for (int i = 0; i < size.x; ++i) {
        const glm::vec3 p = scene.grid.origin + (glm::vec3(i, j, k) + 0.5f) * dx;
        const float h = (p.y - source.y) / height;  // 0 at the source, 1 at the top
        if (h < 0 || h > 1) continue;
        bool solid = false;
        for (const scene::Obstacle& o : scene.obstacles)
          if (const auto* s = std::get_if<scene::SphereObstacle>(&o.shape))
            solid = solid || glm::distance(p, s->center) < s->radius;
        if (solid) continue;
        // A column that sways and widens with height (radius 0.1 → 0.35 of the domain's width), fading out
        // over its top fifth, modulated by two octaves of noise at 0.1 m and 0.05 m.
        const glm::vec2 axis = glm::vec2(source.x, source.z) +
                               0.05f * extent.x * glm::vec2(std::sin(6.0f * h), std::cos(4.0f * h) - 1.0f);
        const float radius = (0.1f + 0.25f * h) * extent.x;
        const float r = glm::distance(glm::vec2(p.x, p.z), axis) / radius;
        const float noise = 0.65f * valueNoise(p * 10.0f) + 0.35f * valueNoise(p * 20.0f + 17.0f);
        const float fade = std::min(1.0f, 5.0f * (1.0f - h));
        const float density = std::exp(-2.0f * r * r) * fade * (0.3f + 1.4f * noise);
        if (density < 1e-3f) continue;
        smoke[(size_t(k) * size.y + j) * size.x + i] = {density, inlet.temperature * std::min(1.0f, density)};
      }
  return smoke;
}

}  // namespace sixway::app
