#pragma once
// The product's lightmap source: the network of a weights file run on the frame's guiding map (stage
// "network"), with the guide it was trained on.
#include <memory>

#include "nn/network.h"
#include "render/lightmap_repack.h"
#include "runtime/lightmap_source.h"

namespace sixway::runtime {

class NetworkLightmaps : public LightmapSource {
 public:
  // For the scene's lightmap size, its smoke's emission and albedo. Throws io::InputError naming the weights
  // when the network cannot be built from them.
  NetworkLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache, const scene::Scene& scene,
                   const io::SafetensorsFile& weights, bool fp16);
  // Runs `other`'s network (its weights, pipelines and feature maps; nothing more is allocated): the scenes'
  // lightmap sizes and emission must agree (std::invalid_argument naming what differs). The frames that use
  // it must run one after another (one queue: sixway's full barriers order them); each writes its own
  // albedo into its command buffer.
  NetworkLightmaps(const scene::Scene& scene, const NetworkLightmaps& other);

  // The scene's guide with the fine alpha (channel A) when the network reads it (the graph's
  // guide_alpha_step_voxels wins over the scene's render.guide_alpha_step_voxels: the network was trained on
  // that step), and the emission image when its guide has a 5th channel.
  render::GuideSettings guide(const scene::Scene& scene) const override;
  void record(gpu::Sequence& sequence, RealtimeFrame& frame) override;
  // Sets this scene's albedo, which the next recording of the frame writes into its command buffer.
  render::ImagePlane update(RealtimeFrame& frame, const SourceFrame& current) override;
  // From now on the lightmaps are also written in `packing` after the network (stage "repack"); Unity's
  // needs no pass (the frame's own A and B). Before the frame is recorded.
  void packLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache,
                     const render::ChannelPacking& packing);
  // The lightmaps in that packing, or nullptr for Unity's.
  const render::LightmapRepack* packed() const { return packed_.get(); }

 private:
  std::shared_ptr<nn::Network> network_;
  std::unique_ptr<render::LightmapRepack> packed_;
  float albedo_;
  uint32_t size_;
  bool emission_;
};

}  // namespace sixway::runtime
