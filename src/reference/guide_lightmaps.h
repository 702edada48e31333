#pragma once
// Guide-lit lightmaps: the guiding map turned into six-way lightmaps without the network, every light
// direction lit by the mean of the guide lights (shaders/render/guide_lightmaps.comp). The evaluation's
// "guide only" baseline: what the network adds over the guiding map alone.
#include <cstdint>
#include <memory>

namespace sixway::gpu {
class Context;
class Image;
class Pipeline;
class PipelineCache;
class Sequence;
}  // namespace sixway::gpu

namespace sixway::render {
struct LightmapImages;
}  // namespace sixway::render

namespace sixway::reference {

class GuideLightmaps {
 public:
  // For a guiding map made with `guideLights` guide lights (GuideSettings::lights.size(), ≥ 1).
  GuideLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache, uint32_t guideLights);
  ~GuideLightmaps();

  // Records the stage "guide lightmaps": `guide` (RGBA16F) into `lightmaps` of the same size. Throws
  // std::invalid_argument for images of different sizes.
  void record(gpu::Sequence& sequence, const gpu::Image& guide,
              const render::LightmapImages& lightmaps) const;

 private:
  std::unique_ptr<gpu::Pipeline> pass_;
};

}  // namespace sixway::reference
