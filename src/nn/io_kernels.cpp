#include "nn/io_kernels.h"

#include <algorithm>

#include "gpu/check.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "nn/nn_spec.h"

namespace sixway::nn {

InputKernel::InputKernel(const KernelSetup& setup, MapShape map, uint32_t guideWidth, uint32_t guideHeight,
                         int guideChannels, int albedoChannel)
    : map_(map),
      guideChannels_(guideChannels),
      sampler_(std::make_unique<gpu::Sampler>(*setup.context, VK_FILTER_NEAREST)) {
  if (map.channels > 8 || guideChannels > int(std::min<uint32_t>(map.channels, kMaxGuideChannels)))
    throw gpu::GpuError("network input: " + std::to_string(guideChannels) + " guide channels into a map of " +
                        std::to_string(map.channels));
  gpu::ComputePipelineDesc desc;
  desc.shader = shaderName("input", setup.precision);
  desc.bindings = {gpu::BindingType::SampledImage, gpu::BindingType::StorageBuffer,
                   gpu::BindingType::SampledImage, gpu::BindingType::StorageBuffer};
  desc.spec.set(spec::kLocalSizeX, kTile).set(spec::kLocalSizeY, kTile);
  desc.spec.set(spec::kWidth, int(map.width)).set(spec::kHeight, int(map.height));
  desc.spec.set(spec::kChannels, int(map.channels));
  desc.spec.set(spec::kGuideWidth, int(guideWidth)).set(spec::kGuideHeight, int(guideHeight));
  desc.spec.set(spec::kGuideChannels, guideChannels);
  desc.spec.set(spec::kAlbedoChannel, albedoChannel);
  pipeline_ = &setup.pipelines->get(desc);
}

void InputKernel::record(gpu::Sequence& sequence, const gpu::Image& guide, const gpu::Image* emission,
                         const gpu::Buffer& scene, const FeatureMap& output) const {
  if (guideChannels_ > kGuideImageChannels && !emission)
    throw gpu::GpuError("network input: the guide's 5th channel needs an emission image");
  // Without an emission channel the guide stands in for the unread second image.
  sequence.dispatch(*pipeline_,
                    {gpu::samples(guide, *sampler_), gpu::writes(output.buffer()),
                     gpu::samples(emission ? *emission : guide, *sampler_), gpu::reads(scene)},
                    std::span<const std::byte>(), groupsFor(map_.width, kTile),
                    groupsFor(map_.height, kTile));
}

OutputLayout outputLayout(const Node& output, const std::vector<int>& inputChannels, bool emission) {
  OutputLayout layout;
  int k = 0;
  for (size_t input = 0; input < inputChannels.size(); ++input)
    for (int c = 0; c < inputChannels[input]; ++c) layout.source.at(k++) = int(input) * 4 + c;
  if (!emission)
    for (int i = 0; i < 8; ++i)
      if (output.channels.at(i) == "emissive") layout.source[i] = -1;
  for (int i = 0; i < 8; ++i) layout.encoding[i] = output.encodings.at(i);
  layout.lightmapA = output.lightmapA;
  layout.lightmapB = output.lightmapB;
  return layout;
}

OutputKernel::OutputKernel(const KernelSetup& setup, const OutputLayout& layout, const MapShape& map,
                           uint32_t width, uint32_t height)
    : width_(width), height_(height) {
  gpu::ComputePipelineDesc desc;
  desc.shader = shaderName("output", setup.precision);
  using gpu::BindingType;
  desc.bindings = {BindingType::StorageTexelBuffer, BindingType::StorageTexelBuffer,
                   BindingType::StorageTexelBuffer, BindingType::StorageTexelBuffer,
                   BindingType::StorageImage,       BindingType::StorageImage};
  int srgbMask = 0;
  for (int k = 0; k < 8; ++k)
    if (layout.encoding[k] == Encoding::Srgb) srgbMask |= 1 << k;
  desc.spec.set(spec::kLocalSizeX, kTile).set(spec::kLocalSizeY, kTile);
  desc.spec.set(spec::kWidth, int(width)).set(spec::kHeight, int(height));
  desc.spec.set(spec::kMapWidth, int(map.width)).set(spec::kMapHeight, int(map.height));
  desc.spec.set(spec::kSrgbMask, srgbMask);
  for (int k = 0; k < 8; ++k) desc.spec.set(spec::kSource[k], layout.source[k]);
  for (int k = 0; k < 4; ++k)
    desc.spec.set(spec::kLightmapA[k], layout.lightmapA[k]).set(spec::kLightmapB[k], layout.lightmapB[k]);
  pipeline_ = &setup.pipelines->get(desc);
}

void OutputKernel::record(gpu::Sequence& sequence, const std::vector<const FeatureMap*>& heads,
                          const gpu::Image& lightmapA, const gpu::Image& lightmapB) const {
  if (heads.empty() || heads.size() > 4) throw gpu::GpuError("output kernel: needs 1 to 4 head maps");
  std::vector<gpu::Binding> bindings;
  for (size_t i = 0; i < 4; ++i)
    bindings.push_back(gpu::reads(heads[std::min(i, heads.size() - 1)]->texels()));
  bindings.push_back(gpu::writes(lightmapA));
  bindings.push_back(gpu::writes(lightmapB));
  sequence.dispatch(*pipeline_, bindings, std::span<const std::byte>(), groupsFor(width_, kTile),
                    groupsFor(height_, kTile));
}

}  // namespace sixway::nn
