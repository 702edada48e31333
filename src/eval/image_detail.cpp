#include "eval/image_detail.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sixway::eval {
namespace {

// Clipped linear luminance (Rec. 709) of every pixel.
std::vector<float> luminance(const io::Image& rgba) {
  if (rgba.channelCount() != 4) throw std::invalid_argument("image detail: the image is not RGBA");
  std::vector<float> y(size_t(rgba.width) * rgba.height);
  const auto clip = [](float v) { return std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f); };
  for (size_t p = 0; p < y.size(); ++p)
    y[p] = 0.2126f * clip(rgba.pixels[p * 4]) + 0.7152f * clip(rgba.pixels[p * 4 + 1]) +
           0.0722f * clip(rgba.pixels[p * 4 + 2]);
  return y;
}

// Y − G_σ ∗ Y, the blur separable with the edges clamped.
std::vector<float> highPass(const std::vector<float>& y, int width, int height) {
  const int radius = int(std::ceil(3.0f * kDetailSigma));
  std::vector<float> kernel(2 * radius + 1);
  float sum = 0;
  for (int i = -radius; i <= radius; ++i)
    sum += kernel[i + radius] = std::exp(-0.5f * i * i / (kDetailSigma * kDetailSigma));
  for (float& k : kernel) k /= sum;
  std::vector<float> rows(y.size()), blurred(y.size());
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) {
      float s = 0;
      for (int i = -radius; i <= radius; ++i)
        s += kernel[i + radius] * y[size_t(v) * width + std::clamp(u + i, 0, width - 1)];
      rows[size_t(v) * width + u] = s;
    }
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) {
      float s = 0;
      for (int i = -radius; i <= radius; ++i)
        s += kernel[i + radius] * rows[size_t(std::clamp(v + i, 0, height - 1)) * width + u];
      blurred[size_t(v) * width + u] = y[size_t(v) * width + u] - s;
    }
  return blurred;
}

double maskedEnergy(const std::vector<float>& h, const std::vector<uint8_t>& mask) {
  if (mask.size() != h.size()) throw std::invalid_argument("image detail: the mask is not the image's size");
  double e = 0;
  for (size_t p = 0; p < h.size(); ++p)
    if (mask[p]) e += double(h[p]) * h[p];
  return e;
}

}  // namespace

double highPassEnergy(const io::Image& rgba, const std::vector<uint8_t>& mask) {
  return maskedEnergy(highPass(luminance(rgba), rgba.width, rgba.height), mask);
}

double highPassEnergyOfDifference(const io::Image& a, const io::Image& b, const std::vector<uint8_t>& mask) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument("image detail: the images differ in size");
  std::vector<float> d = luminance(a);
  const std::vector<float> yb = luminance(b);
  for (size_t p = 0; p < d.size(); ++p) d[p] -= yb[p];
  return maskedEnergy(highPass(d, a.width, a.height), mask);
}

std::vector<uint8_t> smokeMask(const io::Image& truth) {
  if (truth.channelCount() != 4) throw std::invalid_argument("image detail: the truth is not RGBA");
  std::vector<uint8_t> mask(size_t(truth.width) * truth.height);
  for (size_t p = 0; p < mask.size(); ++p) mask[p] = truth.pixels[p * 4 + 3] > 0.01f;
  return mask;
}

}  // namespace sixway::eval
