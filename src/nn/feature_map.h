#pragma once
// A feature map of the network on the GPU: C channels of an H x W map in one buffer of RGBA texels, as
// ceil(C/4) channel groups of H + 2 rows, each group framed by a one-texel zero border (the layout of
// shaders/common/nn_tensor.glsl). Kernels write it as a storage buffer and read it through a texel view. The
// border and the channels past C stay zero: kernels read one pixel outside the map, or a whole padded group,
// without bounds checks.
#include <cstdint>
#include <string>
#include <vector>

#include "gpu/buffer.h"

namespace sixway::gpu {
class Context;
}

namespace sixway::nn {

// Fp16 stores the maps as RGBA16F (the shaders' NN_FP16 variants); arithmetic is fp32 either way.
enum class Precision { Fp32, Fp16 };

struct MapShape {
  uint32_t width = 1, height = 1, channels = 1;
  uint32_t groups() const { return (channels + 3) / 4; }
  bool operator==(const MapShape&) const = default;
};

// Texels a kernel may read past the map's width (blocks of up to 8 input pixels along x), and rows past the
// last group's (blocks of up to 16 input rows): what lies there only feeds outputs outside the map.
constexpr uint32_t kMapSlack = 8;
constexpr uint32_t kMapSlackRows = 16;

class FeatureMap {
 public:
  // Throws gpu::GpuError when fp16 is asked of a device without 16-bit storage buffers.
  FeatureMap(const gpu::Context& context, MapShape shape, Precision precision, std::string name);

  const MapShape& shape() const { return shape_; }
  Precision precision() const { return precision_; }
  const gpu::Buffer& buffer() const { return buffer_; }    // bound with gpu::writes
  const gpu::BufferView& texels() const { return view_; }  // bound with gpu::reads

  // Channel-major values (PyTorch's C x H x W); for tests and tools, not per frame.
  void upload(const std::vector<float>& chw);
  std::vector<float> download() const;

 private:
  size_t texelOf(uint32_t c, uint32_t x,
                 uint32_t y) const;  // index of channel c of pixel (x, y) among floats

  MapShape shape_;
  Precision precision_;
  uint32_t rowTexels_ = 0, rows_ = 0;
  gpu::Buffer buffer_;
  gpu::BufferView view_;
};

}  // namespace sixway::nn
