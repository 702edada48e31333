#pragma once
// Conv2d (kernel 1 or 3, stride 1 or 2, zero padding) over one or two concatenated feature maps, and
// ConvTranspose2d (kernel 2, stride 2), each followed by bias and activation: shaders/nn/conv2d.comp and
// conv_transpose2x2.comp. Weights live in uniform buffers of at most 64 KiB, so a layer's output channel
// groups are split into chunks, one buffer each.
#include <string>
#include <vector>

#include "gpu/buffer.h"
#include "nn/feature_map.h"
#include "nn/graph.h"
#include "nn/kernel.h"

namespace sixway::gpu {
class Pipeline;
class Sequence;
}  // namespace sixway::gpu

namespace sixway::nn {

struct ConvShape {
  uint32_t inWidth = 1, inHeight = 1;
  std::vector<int>
      inputChannels;  // one entry per concatenated input (at most two for conv2d, one if transposed)
  int outChannels = 1;
  int kernel = 3, stride = 1;
  bool transposed = false;  // ConvTranspose2d: kernel 2, stride 2
  Activation activation = Activation::None;
  float negativeSlope = 0.0f;
  // Per invocation, 0 chooses from the map size: conv2d's output rows (1, 2, 4 or 8), and pixels along x
  // (conv2d: output pixels, 1, 2 or 4; transposed: input pixels, 1 to 8).
  int rows = 0;
  int pixels = 0;

  int inChannels() const;
  MapShape output() const;
  double flops() const;  // 2 per multiply-add over the real channels
};

class ConvKernel {
 public:
  // weight: PyTorch's layout ([out][in][k][k], or [in][out][2][2] when transposed); bias: [out].
  ConvKernel(const KernelSetup& setup, const ConvShape& shape, const std::vector<float>& weight,
             const std::vector<float>& bias, const std::string& name);

  const ConvShape& shape() const { return shape_; }
  void record(gpu::Sequence& sequence, const std::vector<const FeatureMap*>& inputs,
              const FeatureMap& output) const;

 private:
  ConvShape shape_;
  const gpu::Pipeline* pipeline_;
  std::vector<gpu::Buffer> chunks_;  // the weights of groupsPerChunk_ output groups each
  int groupsPerChunk_ = 1, outGroups_ = 1;
  uint32_t gridX_ = 1, gridY_ = 1;
};

}  // namespace sixway::nn
