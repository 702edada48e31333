#pragma once
// PyTorch weights rearranged into the vec4 layouts the kernels read from uniform buffers. Channels live in
// groups of 4 (a feature map texel); a layout says where each real channel sits among the padded ones, and
// the padding gets zero weights, so padded channels stay zero through every layer.
#include <cstddef>
#include <vector>

namespace sixway::nn {

struct ChannelLayout {
  std::vector<int> index;  // padded position of each real channel
  int padded = 0;          // 4 x the number of groups

  int groups() const { return padded / 4; }
};

// Inputs concatenated along channels, each padded to whole groups (concatenation by addressing).
ChannelLayout concatLayout(const std::vector<int>& channelsPerInput);
// One tensor padded to whole groups.
ChannelLayout plainLayout(int channels);
// SimpleGate order: the two halves of `channels`, each padded to whole groups.
ChannelLayout gateLayout(int channels);

// For each output group: for each padded input channel, for each tap, the vec4 of the group's 4 output
// channels; then, with a bias, the bias vec4. `weight` is [out][in][taps] (PyTorch Conv2d, taps = kh x kw).
std::vector<float> packConvolution(const std::vector<float>& weight, const std::vector<float>* bias, int taps,
                                   const ChannelLayout& out, const ChannelLayout& in);

// conv2d_matrix.comp's weight matrix W[k][o], `rows` x `columns` row-major and zero past the layer: k = tap x
// in.padded + the input channel's padded position, o the output channel. `weight` is [out][in][taps].
std::vector<float> packMatrix(const std::vector<float>& weight, int taps, int outChannels,
                              const ChannelLayout& in, size_t rows, size_t columns);

// ConvTranspose2d's [in][out][taps] weight reordered to Conv2d's [out][in][taps].
std::vector<float> swapInOut(const std::vector<float>& weight, int inChannels, int outChannels, int taps);

// A per-channel vector (bias, LayerNorm affine, beta, gamma) in padded order.
std::vector<float> packChannels(const std::vector<float>& values, const ChannelLayout& layout);

// Depthwise 3x3 (weight [C][1][3][3], bias [C]): for each padded group, the 9 taps then the bias, vec4 each.
std::vector<float> packDepthwise(const std::vector<float>& weight, const std::vector<float>& bias,
                                 const ChannelLayout& layout);

}  // namespace sixway::nn
