#pragma once
// NAFBlock of NAFNet (Chen et al. 2022) in four kernels: naf_norm_expand (LayerNorm + 1x1 expand),
// naf_dw_gate (3x3 depthwise + SimpleGate + channel sums), naf_attention (global average + 1x1, folded into
// conv3's weights) and naf_tail (conv3, beta residual, LayerNorm, 1x1, SimpleGate, 1x1, gamma residual).
#include <array>
#include <map>
#include <string>
#include <vector>

#include "gpu/buffer.h"
#include "nn/feature_map.h"
#include "nn/kernel.h"

namespace sixway::gpu {
class Pipeline;
class Sequence;
}  // namespace sixway::gpu

namespace sixway::nn {

// A block's parameters by their name within the block ("norm1.weight", "conv2.bias", "beta", ...); with a
// projection, also "projection.weight" ([P][C][1][1]) and "projection.bias".
using ParameterMap = std::map<std::string, std::vector<float>>;

struct NafShape {
  uint32_t width = 1, height = 1;
  int channels = 4;
  int dwExpand = 2, ffnExpand = 2;
  float eps = 1e-6f;
  int projection = 0;  // > 0: a fused 1x1 conv to this many channels follows the block (an adapter's head)

  int gated() const { return channels * dwExpand / 2; }  // channels after the first SimpleGate
  int ffn() const { return channels * ffnExpand / 2; }   // after the second
  MapShape map() const { return {width, height, uint32_t(channels)}; }
  MapShape output() const { return {width, height, uint32_t(projection ? projection : channels)}; }
  double flops() const;  // 2 per multiply-add of the convolutions (not normalisation or elementwise work)
  // flops() split over the four kernels (the attention's per-image 1x1 conv counts as nothing; the projection
  // counts in the last).
  std::array<double, 4> kernelFlops() const;
};

class NafBlockKernel {
 public:
  NafBlockKernel(const KernelSetup& setup, const NafShape& shape, const ParameterMap& parameters,
                 const std::string& name);

  const NafShape& shape() const { return shape_; }
  // With `timedAs`, each of the four kernels is a timed stage "<timedAs>/<kernel>".
  void record(gpu::Sequence& sequence, const FeatureMap& input, const FeatureMap& output,
              const std::string& timedAs = "") const;
  static constexpr uint32_t kStages = 4;

 private:
  NafShape shape_;
  const gpu::Pipeline *normExpand_, *dwGate_, *attention_, *tail_;
  gpu::Buffer normExpandWeights_, dwGateWeights_, attentionWeights_, tailWeights_;
  gpu::Buffer partials_;     // per dw_gate workgroup and gated channel group: the sum of the gated values
  gpu::Buffer scaledConv3_;  // written by naf_attention, read by naf_tail as a uniform buffer
  FeatureMap expanded_, gated_;
  uint32_t expandGrid_[2], dwGrid_[2], tailGrid_[2];
};

}  // namespace sixway::nn
