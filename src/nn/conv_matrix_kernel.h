#pragma once
// Conv2d (kernel 1 or 3, stride 1 or 2, zero padding, one or two concatenated inputs, bias, activation) of
// fp16 maps on cooperative matrices: shaders/nn/conv2d_matrix.comp, an implicit matrix product on an NVIDIA
// GPU's tensor cores (gpu/cooperative_matrix.h). The same layer as ConvKernel computes, with the weights
// rounded to fp16.
#include <string>
#include <vector>

#include "gpu/buffer.h"
#include "nn/conv_kernel.h"
#include "nn/feature_map.h"
#include "nn/kernel.h"

namespace sixway::nn {

class ConvMatrixKernel {
 public:
  // Throws gpu::GpuError on a device without cooperative matrices, for fp32 maps, or for a transposed layer.
  ConvMatrixKernel(const KernelSetup& setup, const ConvShape& shape, const std::vector<float>& weight,
                   const std::vector<float>& bias, const std::string& name);

  const ConvShape& shape() const { return shape_; }
  void record(gpu::Sequence& sequence, const std::vector<const FeatureMap*>& inputs,
              const FeatureMap& output) const;

 private:
  ConvShape shape_;
  const gpu::Pipeline* pipeline_;
  gpu::Buffer weights_, bias_;
  uint32_t gridX_ = 1, gridY_ = 1;
};

}  // namespace sixway::nn
