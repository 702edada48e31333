#include "render/light_grid.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

#include "gpu/pipeline.h"

namespace sixway::render {

LightGrid lightGridFor(const VolumeGrid& volume, glm::vec3 toLight, glm::vec3 u, glm::vec3 v, float spacing,
                       float maxStep) {
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
  g.nodes = glm::ivec3(glm::ceil(extent / spacing - 1e-4f)) + 1;
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
