#include "eval/shard_network.h"

#include <algorithm>
#include <span>

#include "nn/graph.h"

namespace sixway::eval {
namespace {

nn::NetworkOptions networkOptions(float albedo) {
  nn::NetworkOptions options;
  options.albedo = albedo;
  return options;
}

gpu::ImageDesc guideImage(int size, VkFormat format, const char* name) {
  return {uint32_t(size),
          uint32_t(size),
          1,
          format,
          VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
          name};
}

// For a network that reads the guide's emission: its image.
std::unique_ptr<gpu::Image> emissionImage(const gpu::Context& context, const nn::Network& network, int size) {
  if (network.graph().nodes.front().guideChannels <= nn::kGuideImageChannels) return nullptr;
  return std::make_unique<gpu::Image>(context, guideImage(size, VK_FORMAT_R32_SFLOAT, "guide emission"));
}

}  // namespace

ShardNetwork::ShardNetwork(const gpu::Context& context, const gpu::PipelineCache& cache,
                           const io::SafetensorsFile& weights, int size, float albedo)
    : size_(size),
      network_(context, cache, weights, uint32_t(size), uint32_t(size), networkOptions(albedo)),
      lightmaps_(context, uint32_t(size), uint32_t(size)),
      guide_(context, guideImage(size, VK_FORMAT_R32G32B32A32_SFLOAT, "guide")),
      emission_(emissionImage(context, network_, size)),
      sequence_(context) {
  sequence_.beginStage("network");
  network_.record(sequence_, {guide_, emission_.get()}, lightmaps_.a, lightmaps_.b);
  sequence_.endStage();
  sequence_.finish();
}

io::Image ShardNetwork::infer(const std::vector<float>& guide, int channels) {
  const size_t pixels = size_t(size_) * size_t(size_);
  std::vector<float> rgba(pixels * 4, 0.0f), emitted(pixels, 0.0f);
  for (size_t p = 0; p < pixels; ++p) {
    for (int c = 0; c < std::min(channels, nn::kGuideImageChannels); ++c)
      rgba[p * 4 + c] = guide[p * channels + c];
    if (channels > nn::kGuideImageChannels) emitted[p] = guide[p * channels + 4];
  }
  guide_.upload(std::as_bytes(std::span(rgba)));
  if (emission_) emission_->upload(std::as_bytes(std::span(emitted)));
  sequence_.submit();
  return lightmaps_.download();
}

}  // namespace sixway::eval
