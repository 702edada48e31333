#include "nn/upsample_kernel.h"

#include "gpu/pipeline.h"
#include "gpu/sequence.h"

namespace sixway::nn {

UpsampleKernel::UpsampleKernel(const KernelSetup& setup, MapShape input, int factor)
    : input_(input), factor_(uint32_t(factor)) {
  gpu::ComputePipelineDesc desc;
  desc.shader = shaderName("upsample_bilinear", setup.precision);
  desc.bindings = {gpu::BindingType::StorageTexelBuffer, gpu::BindingType::StorageBuffer};
  desc.spec.set(0, kTile).set(1, kTile).set(2, int(input.width)).set(3, int(input.height));
  desc.spec.set(4, int(input.groups())).set(5, factor);
  pipeline_ = &setup.pipelines->get(desc);
}

void UpsampleKernel::record(gpu::Sequence& sequence, const FeatureMap& input,
                            const FeatureMap& output) const {
  const MapShape out = this->output();
  sequence.dispatch(*pipeline_, {gpu::reads(input.texels()), gpu::writes(output.buffer())},
                    std::span<const std::byte>(), groupsFor(out.width, kTile), groupsFor(out.height, kTile));
}

}  // namespace sixway::nn
