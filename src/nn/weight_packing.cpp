#include "nn/weight_packing.h"

#include <stdexcept>

namespace sixway::nn {

ChannelLayout concatLayout(const std::vector<int>& channelsPerInput) {
  ChannelLayout layout;
  for (int channels : channelsPerInput) {
    for (int c = 0; c < channels; ++c) layout.index.push_back(layout.padded + c);
    layout.padded += (channels + 3) / 4 * 4;
  }
  return layout;
}

ChannelLayout plainLayout(int channels) {
  return concatLayout({channels});
}

ChannelLayout gateLayout(int channels) {
  if (channels % 2) throw std::invalid_argument("gateLayout: SimpleGate needs an even channel count");
  return concatLayout({channels / 2, channels / 2});
}

std::vector<float> packConvolution(const std::vector<float>& weight, const std::vector<float>* bias, int taps,
                                   const ChannelLayout& out, const ChannelLayout& in) {
  const size_t outChannels = out.index.size(), inChannels = in.index.size();
  if (weight.size() != outChannels * inChannels * taps || (bias && bias->size() != outChannels))
    throw std::invalid_argument("packConvolution: weight or bias size does not match the layouts");
  const size_t groupFloats = size_t(in.padded) * taps * 4 + (bias ? 4 : 0);
  std::vector<float> packed(size_t(out.groups()) * groupFloats, 0.0f);
  for (size_t o = 0; o < outChannels; ++o) {
    const size_t group = out.index[o] / 4, lane = out.index[o] % 4;
    float* base = &packed[group * groupFloats];
    for (size_t i = 0; i < inChannels; ++i)
      for (int t = 0; t < taps; ++t)
        base[(size_t(in.index[i]) * taps + t) * 4 + lane] = weight[(o * inChannels + i) * taps + t];
    if (bias) base[groupFloats - 4 + lane] = (*bias)[o];
  }
  return packed;
}

std::vector<float> packMatrix(const std::vector<float>& weight, int taps, int outChannels,
                              const ChannelLayout& in, size_t rows, size_t columns) {
  const size_t inChannels = in.index.size();
  if (weight.size() != size_t(outChannels) * inChannels * taps || size_t(taps) * in.padded > rows ||
      size_t(outChannels) > columns)
    throw std::invalid_argument("packMatrix: weight size or matrix shape does not match the layer");
  std::vector<float> matrix(rows * columns, 0.0f);
  for (size_t o = 0; o < size_t(outChannels); ++o)
    for (size_t i = 0; i < inChannels; ++i)
      for (int t = 0; t < taps; ++t)
        matrix[(size_t(t) * in.padded + in.index[i]) * columns + o] = weight[(o * inChannels + i) * taps + t];
  return matrix;
}

std::vector<float> swapInOut(const std::vector<float>& weight, int inChannels, int outChannels, int taps) {
  std::vector<float> swapped(weight.size());
  for (int i = 0; i < inChannels; ++i)
    for (int o = 0; o < outChannels; ++o)
      for (int t = 0; t < taps; ++t)
        swapped[(size_t(o) * inChannels + i) * taps + t] = weight[(size_t(i) * outChannels + o) * taps + t];
  return swapped;
}

std::vector<float> packChannels(const std::vector<float>& values, const ChannelLayout& layout) {
  std::vector<float> packed(layout.padded, 0.0f);
  for (size_t c = 0; c < values.size(); ++c) packed[layout.index.at(c)] = values[c];
  return packed;
}

std::vector<float> packDepthwise(const std::vector<float>& weight, const std::vector<float>& bias,
                                 const ChannelLayout& layout) {
  std::vector<float> packed(size_t(layout.groups()) * 10 * 4, 0.0f);
  for (size_t c = 0; c < layout.index.size(); ++c) {
    const size_t group = layout.index[c] / 4, lane = layout.index[c] % 4;
    for (int t = 0; t < 9; ++t) packed[(group * 10 + t) * 4 + lane] = weight[c * 9 + t];
    packed[(group * 10 + 9) * 4 + lane] = bias[c];
  }
  return packed;
}

}  // namespace sixway::nn
