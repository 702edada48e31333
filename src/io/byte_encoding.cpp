#include "io/byte_encoding.h"

#include <algorithm>
#include <cmath>

namespace sixway::io {
namespace {

float srgbEncode(float linear) {
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

uint8_t toByte(float value, bool applySrgb) {
  const float clipped = value > 0.0f ? std::min(value, 1.0f) : 0.0f;  // also maps NaN to 0
  return static_cast<uint8_t>(std::lround((applySrgb ? srgbEncode(clipped) : clipped) * 255.0f));
}

}  // namespace

std::vector<uint8_t> toBytes(const Image& image, ByteEncoding encoding) {
  const int channels = image.channelCount();
  const bool hasAlpha = channels == 2 || channels == 4;
  std::vector<uint8_t> bytes(image.pixels.size());
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    const bool isAlpha = hasAlpha && static_cast<int>(i % channels) == channels - 1;
    bytes[i] = toByte(image.pixels[i], encoding == ByteEncoding::SRGB && !isAlpha);
  }
  return bytes;
}

}  // namespace sixway::io
