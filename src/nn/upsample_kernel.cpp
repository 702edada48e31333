#include "nn/upsample_kernel.h"

#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "nn/nn_spec.h"

namespace sixway::nn {

UpsampleKernel::UpsampleKernel(const KernelSetup& setup, MapShape input, int factor)
    : input_(input), factor_(uint32_t(factor)) {
  gpu::ComputePipelineDesc desc;
  desc.shader = shaderName("upsample_bilinear", setup.precision);
  desc.bindings = {gpu::BindingType::StorageTexelBuffer, gpu::BindingType::StorageBuffer};
  desc.spec.set(spec::kLocalSizeX, kTile).set(spec::kLocalSizeY, kTile);
  desc.spec.set(spec::kInWidth, int(input.width)).set(spec::kInHeight, int(input.height));
  desc.spec.set(spec::kGroups, int(input.groups())).set(spec::kFactor, factor);
  pipeline_ = &setup.pipelines->get(desc);
}

void UpsampleKernel::record(gpu::Sequence& sequence, const FeatureMap& input,
                            const FeatureMap& output) const {
  const MapShape out = this->output();
  sequence.dispatch(*pipeline_, {gpu::reads(input.texels()), gpu::writes(output.buffer())},
                    std::span<const std::byte>(), groupsFor(out.width, kTile), groupsFor(out.height, kTile));
}

}  // namespace sixway::nn
