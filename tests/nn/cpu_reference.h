#pragma once
// CPU references of the network's layers (test oracles, not product code): straightforward loops over
// channel-major (C x H x W) tensors with double accumulation, following PyTorch's definitions.
#include <string>
#include <vector>

#include "nn/graph.h"
#include "nn/naf_block_kernel.h"

namespace sixway::test {

struct CpuMap {
  int channels = 0, height = 0, width = 0;
  std::vector<float> values;  // channel-major

  CpuMap() = default;
  CpuMap(int c, int h, int w) : channels(c), height(h), width(w), values(size_t(c) * h * w, 0.0f) {}
  float& at(int c, int y, int x) { return values[(size_t(c) * height + y) * width + x]; }
  float at(int c, int y, int x) const { return values[(size_t(c) * height + y) * width + x]; }
};

CpuMap concat(const CpuMap& a, const CpuMap& b);
// Conv2d with zero padding kernel/2; weight [out][in][k][k] (groups = in for depthwise: weight [c][1][k][k]).
CpuMap conv2d(const CpuMap& in, const std::vector<float>& weight, const std::vector<float>& bias,
              int outChannels, int kernel, int stride);
CpuMap depthwise3x3(const CpuMap& in, const std::vector<float>& weight, const std::vector<float>& bias);
// ConvTranspose2d, kernel 2, stride 2; weight [in][out][2][2].
CpuMap convTranspose2x2(const CpuMap& in, const std::vector<float>& weight, const std::vector<float>& bias,
                        int outChannels);
CpuMap activate(CpuMap map, nn::Activation activation, float negativeSlope);
CpuMap upsampleBilinear(const CpuMap& in, int factor);  // align_corners=False
CpuMap layerNorm2d(const CpuMap& in, const std::vector<float>& weight, const std::vector<float>& bias,
                   float eps);
CpuMap simpleGate(const CpuMap& in);
// NAFNet's block, parameters named as in nn::ParameterMap.
CpuMap nafBlock(const CpuMap& in, const nn::ParameterMap& p, float eps);
float srgbToLinear(float v);

}  // namespace sixway::test
