#include "nn/feature_map.h"

#include <stdexcept>

#include "gpu/check.h"
#include "gpu/context.h"
#include "io/safetensors.h"

namespace sixway::nn {
namespace {

uint32_t texelBytes(Precision precision) {
  return precision == Precision::Fp16 ? 8 : 16;
}

// The layout's texels per row and rows, in 64 bits: a huge map (a graph's channels or size_multiple) must
// not wrap to a size that looks allocatable.
uint64_t rowTexelsOf(const MapShape& shape) {
  return (uint64_t(shape.width) + kMapSlack - 1) / kMapSlack * kMapSlack + 2;
}
uint64_t rowsOf(const MapShape& shape) {
  return uint64_t(shape.groups()) * (uint64_t(shape.height) + 2) + kMapSlackRows;
}

// The buffer's bytes; the largest uint64 when they do not fit in one (no device holds that).
uint64_t bufferBytes(const MapShape& shape, Precision precision) {
  uint64_t bytes = 0;
  if (__builtin_mul_overflow(rowTexelsOf(shape), rowsOf(shape), &bytes) ||
      __builtin_mul_overflow(bytes, uint64_t(texelBytes(precision)), &bytes))
    return UINT64_MAX;
  return bytes;
}

}  // namespace

FeatureMap::FeatureMap(const gpu::Context& context, MapShape shape, Precision precision, std::string name)
    : shape_(shape), precision_(precision) {
  if (precision == Precision::Fp16 && !context.capabilities().storage16Bit)
    throw gpu::GpuError(name + ": fp16 feature maps need 16-bit storage buffers, which " +
                        context.properties().deviceName + " lacks; use fp32");
  // The device refuses a buffer beyond its storage-buffer range (at most 4 GiB), so the counts fit 32 bits.
  buffer_ = gpu::Buffer(context, bufferBytes(shape, precision),
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT |
                            VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                        gpu::MemoryKind::Device, std::move(name));
  rowTexels_ = uint32_t(rowTexelsOf(shape));
  rows_ = uint32_t(rowsOf(shape));
  view_ = gpu::BufferView(
      context, buffer_,
      precision == Precision::Fp16 ? VK_FORMAT_R16G16B16A16_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT);
  // Zero once: the borders and padding channels are never written again.
  buffer_.upload(std::vector<std::byte>(buffer_.size()));
}

size_t FeatureMap::texelOf(uint32_t c, uint32_t x, uint32_t y) const {
  const size_t row = (c / 4) * (shape_.height + 2) + y + 1;
  return (row * rowTexels_ + x + 1) * 4 + c % 4;
}

void FeatureMap::upload(const std::vector<float>& chw) {
  if (chw.size() != size_t(shape_.width) * shape_.height * shape_.channels)
    throw std::invalid_argument(buffer_.name() + ": upload of " + std::to_string(chw.size()) + " values");
  std::vector<float> texels(size_t(rowTexels_) * rows_ * 4, 0.0f);
  for (uint32_t c = 0; c < shape_.channels; ++c)
    for (uint32_t y = 0; y < shape_.height; ++y)
      for (uint32_t x = 0; x < shape_.width; ++x)
        texels[texelOf(c, x, y)] = chw[(size_t(c) * shape_.height + y) * shape_.width + x];
  if (precision_ == Precision::Fp32) {
    buffer_.upload(texels);
    return;
  }
  const io::Tensor half = io::Tensor::fromFloat("", io::DType::F16, {int64_t(texels.size())}, texels);
  buffer_.upload(half.bytes);
}

std::vector<float> FeatureMap::download() const {
  std::vector<float> texels;
  if (precision_ == Precision::Fp32) {
    texels = buffer_.download<float>();
  } else {
    const io::Tensor half{"", io::DType::F16, {int64_t(buffer_.size() / 2)}, buffer_.download<uint8_t>()};
    texels = half.toFloat();
  }
  std::vector<float> chw(size_t(shape_.channels) * shape_.height * shape_.width);
  for (uint32_t c = 0; c < shape_.channels; ++c)
    for (uint32_t y = 0; y < shape_.height; ++y)
      for (uint32_t x = 0; x < shape_.width; ++x)
        chw[(size_t(c) * shape_.height + y) * shape_.width + x] = texels[texelOf(c, x, y)];
  return chw;
}

}  // namespace sixway::nn
