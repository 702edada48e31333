#include "render/lightmap_repack.h"

#include <stdexcept>

#include "gpu/pipeline.h"
#include "gpu/sequence.h"

namespace sixway::render {
namespace {

struct RepackPush {
  glm::ivec4 firstSources, secondSources;
};

gpu::Image packedTexture(const gpu::Context& context, uint32_t size, const std::string& name) {
  return gpu::Image(context, {size, size, 1, VK_FORMAT_R16G16B16A16_SFLOAT,
                              VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "lightmap " + name});
}

ChannelPacking twoTexturesWithAlpha(const ChannelPacking& packing) {
  if (packing.textures.size() != 2 || packing.slots[Alpha].texture < 0)
    throw std::invalid_argument("LightmapRepack: a packing of two textures with alpha");
  return packing;
}

}  // namespace

LightmapRepack::LightmapRepack(const gpu::Context& context, const gpu::PipelineCache& cache, uint32_t size,
                               const ChannelPacking& packing)
    : packing_(twoTexturesWithAlpha(packing)),
      textures_{packedTexture(context, size, packing.textures[0]),
                packedTexture(context, size, packing.textures[1])} {
  // Each output component's channel, found in Unity's A (0..3) or B (4..7).
  const ChannelPacking unity = unityPacking();
  sources_[0] = sources_[1] = glm::ivec4(-1);
  for (int channel = 0; channel < kSixWayChannels; ++channel) {
    const ChannelPacking::Slot to = packing_.slots[size_t(channel)], from = unity.slots[size_t(channel)];
    if (to.texture >= 0) sources_[to.texture][to.component] = from.texture * 4 + from.component;
  }
  gpu::ComputePipelineDesc desc;
  desc.shader = "render/repack_lightmaps.comp";
  desc.bindings.assign(4, gpu::BindingType::StorageImage);
  desc.pushConstantBytes = sizeof(RepackPush);
  pipeline_ = std::make_unique<gpu::Pipeline>(context, cache, desc);
}

LightmapRepack::~LightmapRepack() = default;

void LightmapRepack::record(gpu::Sequence& sequence, const LightmapImages& unity) const {
  const uint32_t size = textures_[0].desc().width;
  sequence.beginStage("repack");
  sequence.dispatch(
      *pipeline_,
      {gpu::reads(unity.a), gpu::reads(unity.b), gpu::writes(textures_[0]), gpu::writes(textures_[1])},
      RepackPush{sources_[0], sources_[1]}, (size + 7) / 8, (size + 7) / 8);
  sequence.endStage();
}

}  // namespace sixway::render
