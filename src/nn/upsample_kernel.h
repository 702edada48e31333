#pragma once
// Bilinear upsampling by an integer factor (align_corners=False): shaders/nn/upsample_bilinear.comp.

#include "nn/feature_map.h"
#include "nn/kernel.h"

namespace sixway::gpu {
class Pipeline;
class Sequence;
}  // namespace sixway::gpu

namespace sixway::nn {

class UpsampleKernel {
 public:
  UpsampleKernel(const KernelSetup& setup, MapShape input, int factor);

  MapShape output() const { return {input_.width * factor_, input_.height * factor_, input_.channels}; }
  void record(gpu::Sequence& sequence, const FeatureMap& input, const FeatureMap& output) const;

 private:
  MapShape input_;
  uint32_t factor_;
  const gpu::Pipeline* pipeline_;
};

}  // namespace sixway::nn
