#pragma once
// The network of `sixway eval --dataset` (dataset_eval.h) on the dataset's lightmap size, recorded once: a
// shard sample's guide in, its lightmaps out.
#include <memory>
#include <vector>

#include "gpu/image.h"
#include "gpu/sequence.h"
#include "io/image.h"
#include "io/safetensors.h"
#include "nn/network.h"
#include "render/lightmap_images.h"

namespace sixway::eval {

class ShardNetwork {
 public:
  // `albedo`: the smoke's, for a network that reads it.
  ShardNetwork(const gpu::Context& context, const gpu::PipelineCache& cache,
               const io::SafetensorsFile& weights, int size, float albedo);

  int size() const { return size_; }
  const nn::Graph& graph() const { return network_.graph(); }
  void setAlbedo(float albedo) { network_.setAlbedo(albedo); }
  // One sample's guide, pixel-interleaved with `channels` channels (RGBA, then the emission), through the
  // network: its eight lightmap channels.
  io::Image infer(const std::vector<float>& guide, int channels);
  // The network's GPU time in the last infer().
  double lastMilliseconds() const { return sequence_.stageTimes().front().milliseconds; }

 private:
  int size_;
  nn::Network network_;
  render::LightmapImages lightmaps_;
  gpu::Image guide_;
  std::unique_ptr<gpu::Image> emission_;  // for a network that reads the guide's emission
  gpu::Sequence sequence_;
};

}  // namespace sixway::eval
