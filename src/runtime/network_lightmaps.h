#pragma once
// The product's lightmap source: the network of a weights file run on the frame's guiding map (stage
// "network"), with the guide it was trained on.
#include <filesystem>
#include <memory>

#include "nn/network.h"
#include "runtime/lightmap_source.h"

namespace sixway::runtime {

class NetworkLightmaps : public LightmapSource {
 public:
  // For the scene's lightmap size, its smoke's emission and albedo. Throws io::InputError naming a missing or
  // malformed weights file.
  NetworkLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache, const scene::Scene& scene,
                   const std::filesystem::path& weights, bool fp16);

  // The scene's guide with the fine alpha (channel A) when the network reads it (the graph's
  // guide_alpha_step_voxels wins over the scene's render.guide_alpha_step_voxels: the network was trained on
  // that step), and the emission image when its guide has a 5th channel.
  render::GuideSettings guide(const scene::Scene& scene) const override;
  void record(gpu::Sequence& sequence, RealtimeFrame& frame) override;

 private:
  std::unique_ptr<nn::Network> network_;
};

}  // namespace sixway::runtime
