#pragma once
// The majorant pass of the volume marchers (shaders/render/majorant.comp): per brick of cells, the largest
// density a trilinear lookup can return there. The baker and the guiding map skip the bricks where it is 0;
// the path tracer uses it as the majorant of delta and ratio tracking.
#include <cstdint>
#include <glm/vec3.hpp>
#include <memory>

#include "render/volume.h"

namespace sixway::gpu {
class Buffer;
class Context;
class Pipeline;
class PipelineCache;
class Sequence;
}  // namespace sixway::gpu

namespace sixway::render {

class BrickMajorantPass {
 public:
  BrickMajorantPass(const gpu::Context& context, const gpu::PipelineCache& cache);
  ~BrickMajorantPass();

  // Bricks per axis of `grid` for bricks of brickCells³ cells, and the bytes of their majorant buffer.
  static glm::ivec3 brickCount(const VolumeGrid& grid, int brickCells);
  static uint64_t bufferBytes(const VolumeGrid& grid, int brickCells);

  // One float per brick, x fastest, into `majorants` (at least bufferBytes()).
  void record(gpu::Sequence& sequence, const Volume& volume, int brickCells,
              const gpu::Buffer& majorants) const;

 private:
  std::unique_ptr<gpu::Pipeline> pipeline_;
};

}  // namespace sixway::render
