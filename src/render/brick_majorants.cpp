#include "render/brick_majorants.h"

#include <glm/vec4.hpp>

#include "gpu/pipeline.h"
#include "gpu/sequence.h"

namespace sixway::render {
namespace {

struct BrickPush {  // majorant.comp
  glm::ivec4 size, bricks;
};

uint32_t groupsOf4(int count) {
  return uint32_t((count + 3) / 4);
}

}  // namespace

BrickMajorantPass::BrickMajorantPass(const gpu::Context& context, const gpu::PipelineCache& cache)
    : pipeline_(std::make_unique<gpu::Pipeline>(
          context, cache,
          gpu::ComputePipelineDesc{"render/majorant.comp",
                                   {gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer},
                                   sizeof(BrickPush)})) {}

BrickMajorantPass::~BrickMajorantPass() = default;

glm::ivec3 BrickMajorantPass::brickCount(const VolumeGrid& grid, int brickCells) {
  return (grid.size + brickCells - 1) / brickCells;
}

uint64_t BrickMajorantPass::bufferBytes(const VolumeGrid& grid, int brickCells) {
  const glm::ivec3 b = brickCount(grid, brickCells);
  return uint64_t(b.x) * uint64_t(b.y) * uint64_t(b.z) * sizeof(float);
}

void BrickMajorantPass::record(gpu::Sequence& sequence, const Volume& volume, int brickCells,
                               const gpu::Buffer& majorants) const {
  const glm::ivec3 bricks = brickCount(volume.grid, brickCells);
  sequence.dispatch(*pipeline_, {gpu::reads(*volume.density), gpu::writes(majorants)},
                    BrickPush{glm::ivec4(volume.grid.size, 0), glm::ivec4(bricks, brickCells)},
                    groupsOf4(bricks.x), groupsOf4(bricks.y), groupsOf4(bricks.z));
}

}  // namespace sixway::render
