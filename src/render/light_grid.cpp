#include "render/light_grid.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <stdexcept>
#include <string>

#include "gpu/pipeline.h"

namespace sixway::render {
namespace {

// Enough widenings by 1.25 to take kMaxLightGridAxisNodes down to a few nodes (1.25^100 ≈ 5·10⁹).
constexpr int kMaxWidenings = 100;

}  // namespace

int lightGridAxisNodes(float nodes) {
  if (!std::isfinite(nodes) || nodes > float(kMaxLightGridAxisNodes))
    throw std::invalid_argument("light grid: " + std::to_string(nodes) + " nodes along an axis, more than " +
                                std::to_string(kMaxLightGridAxisNodes) +
                                " (is the volume's box beyond a float's range?)");
  return std::max(0, int(nodes));
}

float widenedSpacing(float spacing, const std::function<bool(float)>& fits) {
  if (!(spacing > 0.0f && std::isfinite(spacing)))
    throw std::invalid_argument("light grid: the spacing must be a finite number > 0 (got " +
                                std::to_string(spacing) + ")");
  for (int widenings = 0; widenings < kMaxWidenings; ++widenings, spacing *= 1.25f)
    if (fits(spacing)) return spacing;
  throw std::invalid_argument("light grid: no spacing up to " + std::to_string(spacing) +
                              " m makes the light grids fit the device");
}

LightGrid lightGridFor(const VolumeGrid& volume, glm::vec3 toLight, glm::vec3 u, glm::vec3 v, float spacing,
                       float maxStep) {
  if (!(spacing > 0.0f && std::isfinite(spacing)))
    throw std::invalid_argument("light grid: the spacing must be a finite number > 0 (got " +
                                std::to_string(spacing) + ")");
  const Box box = volume.bounds();
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                      (corner & 4) ? box.max.z : box.min.z);
    const glm::vec3 local(glm::dot(p, u), glm::dot(p, v), glm::dot(p, toLight));
    lo = glm::min(lo, local);
    hi = glm::max(hi, local);
  }
  const glm::vec3 centre = volume.origin + 0.5f * volume.cellSize;
  const glm::vec3 aligned(glm::dot(centre, u), glm::dot(centre, v), glm::dot(centre, toLight));
  // The first node at or below lo (across the light) and at or above hi (along it) that is aligned.
  const glm::vec3 start(aligned.x - std::ceil((aligned.x - lo.x) / spacing) * spacing,
                        aligned.y - std::ceil((aligned.y - lo.y) / spacing) * spacing,
                        aligned.z + std::ceil((hi.z - aligned.z) / spacing) * spacing);
  LightGrid g;
  g.u = u;
  g.v = v;
  g.toLight = toLight;
  g.spacing = spacing;
  g.interval = spacing;
  g.maxStep = maxStep;
  g.corner = start.x * u + start.y * v + start.z * toLight;
  const glm::vec3 extent(hi.x - start.x, hi.y - start.y, start.z - lo.z);
  const glm::vec3 steps = glm::ceil(extent / spacing - 1e-4f);
  g.nodes =
      glm::ivec3(lightGridAxisNodes(steps.x), lightGridAxisNodes(steps.y), lightGridAxisNodes(steps.z)) + 1;
  return g;
}

std::unique_ptr<gpu::Pipeline> lightDepthPipeline(const gpu::Context& context,
                                                  const gpu::PipelineCache& cache) {
  using gpu::BindingType;
  return std::make_unique<gpu::Pipeline>(
      context, cache,
      gpu::ComputePipelineDesc{"render/light_depth.comp",
                               {BindingType::UniformBuffer, BindingType::StorageBuffer,
                                BindingType::StorageBuffer, BindingType::StorageBuffer},
                               sizeof(uint32_t)});
}

}  // namespace sixway::render
