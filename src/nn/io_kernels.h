#pragma once
// The network's ends: the guiding map (and its emission) into the first feature map (shaders/nn/input.comp),
// and the head maps
// out into the two RGBA lightmaps, decoded and packed (shaders/nn/output.comp).
#include <array>
#include <memory>
#include <vector>

#include "gpu/image.h"
#include "nn/feature_map.h"
#include "nn/graph.h"
#include "nn/kernel.h"

namespace sixway::gpu {
class Pipeline;
class Sequence;
}  // namespace sixway::gpu

namespace sixway::nn {

class InputKernel {
 public:
  // `map`: the first feature map (the guide's size rounded up, 4 or 8 channels); the guide is `guideWidth` x
  // `guideHeight`, of `guideChannels` channels: the guide image's first ones, the 5th the emission image's R;
  // `albedoChannel` (-1: none) holds the encoded albedo of the `scene` buffer that record() binds.
  InputKernel(const KernelSetup& setup, MapShape map, uint32_t guideWidth, uint32_t guideHeight,
              int guideChannels, int albedoChannel);
  // `emission`: required with 5 guide channels, unread otherwise; `scene`: one float, the encoded albedo.
  void record(gpu::Sequence& sequence, const gpu::Image& guide, const gpu::Image* emission,
              const gpu::Buffer& scene, const FeatureMap& output) const;

 private:
  MapShape map_;
  int guideChannels_;
  std::unique_ptr<gpu::Sampler> sampler_;
  const gpu::Pipeline* pipeline_;
};

// Where each of the eight output channels comes from, how it is encoded, and where it goes.
struct OutputLayout {
  std::array<int, 8> source{};  // input map * 4 + channel within its first group; -1: the constant 0
  std::array<Encoding, 8> encoding{};
  std::array<int, 4> lightmapA{}, lightmapB{};  // indices into the eight channels
};

// The layout of an output node whose inputs have `inputChannels` channels each (at most 4 each, 4 inputs);
// without `emission` its emissive channel is the constant 0 (NetworkOptions::emission).
OutputLayout outputLayout(const Node& output, const std::vector<int>& inputChannels, bool emission = true);

class OutputKernel {
 public:
  // `map`: the size of the head maps; the lightmaps are `width` x `height` (the maps are cropped to them).
  OutputKernel(const KernelSetup& setup, const OutputLayout& layout, const MapShape& map, uint32_t width,
               uint32_t height);
  // Up to four head maps (missing ones are bound to the first, unread).
  void record(gpu::Sequence& sequence, const std::vector<const FeatureMap*>& heads,
              const gpu::Image& lightmapA, const gpu::Image& lightmapB) const;

 private:
  uint32_t width_, height_;
  const gpu::Pipeline* pipeline_;
};

}  // namespace sixway::nn
