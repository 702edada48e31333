#pragma once
// The frame's lightmaps in an engine's packing (render/lightmap_packing.h): two RGBA16F textures written
// from Unity's A and B (LightmapImages) by shaders/render/repack_lightmaps.comp, for engines that shade the
// billboard with their own material (SmokeRenderer::lightmaps). Unity's packing needs no pass.
#include <array>
#include <glm/vec4.hpp>
#include <memory>

#include "gpu/image.h"
#include "render/lightmap_images.h"
#include "render/lightmap_packing.h"

namespace sixway::gpu {
class Context;
class Pipeline;
class PipelineCache;
class Sequence;
}  // namespace sixway::gpu

namespace sixway::render {

class LightmapRepack {
 public:
  // Two textures of size × size in `packing`. std::invalid_argument for a packing of other than two
  // textures or without alpha.
  LightmapRepack(const gpu::Context& context, const gpu::PipelineCache& cache, uint32_t size,
                 const ChannelPacking& packing);
  ~LightmapRepack();

  // Stage "repack": the textures from `unity` (after the pass that wrote it).
  void record(gpu::Sequence& sequence, const LightmapImages& unity) const;

  const gpu::Image& texture(int index) const { return textures_.at(size_t(index)); }
  const ChannelPacking& packing() const { return packing_; }

 private:
  ChannelPacking packing_;
  std::array<gpu::Image, 2> textures_;
  std::unique_ptr<gpu::Pipeline> pipeline_;
  glm::ivec4 sources_[2];
};

}  // namespace sixway::render
