#include <sixway/lightmap_network.h>

#include <filesystem>
#include <glm/gtc/packing.hpp>
#include <optional>
#include <stdexcept>

#include "gpu/image.h"
#include "gpu/sequence.h"
#include "nn/network.h"
#include "render/lightmap_images.h"
#include "runtime/internal.h"
#include "runtime/network_weights.h"
#include "scene/scene.h"

namespace sixway {

struct LightmapNetwork::Impl {
  Impl(const gpu::Context& context, const gpu::PipelineCache& cache, const io::SafetensorsFile& weights,
       uint32_t size, bool fp16)
      : size(size),
        guide(context, {size, size, 1, VK_FORMAT_R16G16B16A16_SFLOAT,
                        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "guiding map"}),
        lightmaps(context, size, size),
        sequence(context) {
    nn::NetworkOptions options;
    options.precision = fp16 ? nn::Precision::Fp16 : nn::Precision::Fp32;
    options.albedo = scene::Smoke{}.albedo;  // run() sets each run's
    network = runtime::loadNetwork(context, cache, weights, size, options);
    if (network->graph().nodes.front().guideChannels > nn::kGuideImageChannels)
      emission.emplace(
          context, gpu::ImageDesc{size, size, 1, VK_FORMAT_R32_SFLOAT,
                                  VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "guide emission"});
    network->record(sequence, {guide, emission ? &*emission : nullptr}, lightmaps.a, lightmaps.b);
    sequence.finish();
  }
  uint32_t size;
  gpu::Image guide;
  std::optional<gpu::Image> emission;  // for a guide of 5 channels
  render::LightmapImages lightmaps;
  gpu::Sequence sequence;
  std::unique_ptr<nn::Network> network;
};

namespace {

void requireSize(uint32_t size) {
  if (size == 0 || size % 16 != 0)
    throw std::invalid_argument("LightmapNetwork: size must be a multiple of 16");
}

}  // namespace

LightmapNetwork::LightmapNetwork(Device& device, const std::filesystem::path& weights, uint32_t size,
                                 bool fp16) {
  requireSize(size);
  impl_ = std::make_unique<Impl>(runtime::Access::context(device), runtime::Access::pipelineCache(device),
                                 runtime::readWeights(weights), size, fp16);
}

LightmapNetwork::LightmapNetwork(Device& device, std::span<const std::byte> weights, uint32_t size,
                                 bool fp16) {
  requireSize(size);
  impl_ = std::make_unique<Impl>(runtime::Access::context(device), runtime::Access::pipelineCache(device),
                                 runtime::readWeights(weights, {}), size, fp16);
}

LightmapNetwork::~LightmapNetwork() = default;

uint32_t LightmapNetwork::size() const {
  return impl_->size;
}

float LightmapNetwork::fineAlphaStepVoxels() const {
  return impl_->network->graph().nodes.front().guideAlphaStepVoxels;
}

bool LightmapNetwork::readsEmission() const {
  return impl_->emission.has_value();
}

bool LightmapNetwork::readsAlbedo() const {
  return impl_->network->readsAlbedo();
}

std::vector<float> LightmapNetwork::run(std::span<const float> guide, std::span<const float> emission,
                                        float albedo) {
  const size_t pixels = size_t(impl_->size) * impl_->size;
  if (guide.size() != pixels * 4)
    throw std::invalid_argument("LightmapNetwork::run: the guide needs size² RGBA pixels");
  if (emission.size() != (readsEmission() ? pixels : 0))
    throw std::invalid_argument(readsEmission() ? "LightmapNetwork::run: the emission needs size² values"
                                                : "LightmapNetwork::run: this network reads no emission");
  if (!(albedo >= 0.0f && albedo <= 1.0f))
    throw std::invalid_argument("LightmapNetwork::run: the albedo must be in [0, 1]");
  impl_->network->setAlbedo(albedo);
  if (impl_->emission) impl_->emission->upload(std::as_bytes(emission));
  std::vector<uint16_t> halves(guide.size());
  for (size_t i = 0; i < guide.size(); ++i) halves[i] = glm::packHalf1x16(guide[i]);
  impl_->guide.upload(std::as_bytes(std::span(halves)));
  impl_->sequence.submit();
  return impl_->lightmaps.download().pixels;
}

}  // namespace sixway
