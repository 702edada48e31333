#include "metrics/image_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sixway::metrics {
namespace {

float clipped(float v) {
  return std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
}

nlohmann::json number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

}  // namespace

double alphaCoverage(const io::Image& frame, float threshold) {
  if (frame.channelCount() != 4) throw std::invalid_argument("alphaCoverage: the frame has no alpha channel");
  uint64_t covered = 0;
  for (int y = 0; y < frame.height; ++y)
    for (int x = 0; x < frame.width; ++x) covered += frame.at(x, y, 3) >= threshold;
  return double(covered) / double(uint64_t(frame.width) * uint64_t(frame.height));
}

ImageFaults imageFaults(const io::Image& frame) {
  if (frame.channelCount() != 4) throw std::invalid_argument("imageFaults: the frame is not RGBA");
  const int w = frame.width, h = frame.height;
  ImageFaults f;
  const auto note = [&](int x, int y) {
    if (f.first.size() < 8) f.first.push_back({x, y});
  };
  std::vector<float> luminance(size_t(w) * h);
  std::vector<uint8_t> faulty(luminance.size(), 0);
  for (size_t p = 0; p < luminance.size(); ++p) {
    const float* px = &frame.pixels[p * 4];
    bool finite = true, negative = false;
    for (int c = 0; c < 4; ++c)
      finite = finite && std::isfinite(px[c]), negative = negative || px[c] < -1e-6f;
    f.notFinite += !finite;
    f.negative += finite && negative;
    faulty[p] = !finite || negative;
    luminance[p] = finite ? 0.2126f * px[0] + 0.7152f * px[1] + 0.0722f * px[2] : 0.0f;
  }
  // The darkest pixel of the ring four pixels out (the 9 × 9 square's border): a dark dot up to 7 × 7 lies
  // inside.
  constexpr int kRing = 4;
  for (int y = kRing; y + kRing < h; ++y)
    for (int x = kRing; x + kRing < w; ++x) {
      float darkest = std::numeric_limits<float>::max();
      for (int dy = -kRing; dy <= kRing; ++dy)
        for (int dx = -kRing; dx <= kRing; ++dx)
          if (std::abs(dx) == kRing || std::abs(dy) == kRing)
            darkest = std::min(darkest, luminance[size_t(y + dy) * w + x + dx]);
      if (darkest < 0.03f) continue;
      const bool dark = luminance[size_t(y) * w + x] < 0.5f * darkest;
      f.darkDots += dark;
      faulty[size_t(y) * w + x] |= dark;
    }
  for (int y = 0; y < h && f.first.size() < 8; ++y)
    for (int x = 0; x < w; ++x)
      if (faulty[size_t(y) * w + x]) note(x, y);
  return f;
}

std::string describeFaults(const ImageFaults& f) {
  std::string text = std::to_string(f.notFinite) + " non-finite, " + std::to_string(f.negative) +
                     " negative and " + std::to_string(f.darkDots) + " pixels in dark dots";
  if (!f.first.empty())
    text += " (the first at x " + std::to_string(f.first.front()[0]) + ", y " +
            std::to_string(f.first.front()[1]) + ")";
  return text;
}

double psnrDb(double mse) {
  return mse > 0 ? 10.0 * std::log10(1.0 / mse)
                 : (mse == 0 ? std::numeric_limits<double>::infinity()
                             : std::numeric_limits<double>::quiet_NaN());
}

double ImageError::mseMasked() const {
  return valuesMasked ? squaredMasked / double(valuesMasked) : std::numeric_limits<double>::quiet_NaN();
}

double ImageError::mseFull() const {
  return valuesFull ? squaredFull / double(valuesFull) : std::numeric_limits<double>::quiet_NaN();
}

double ImageError::mseBand() const {
  return valuesBand ? squaredBand / double(valuesBand) : std::numeric_limits<double>::quiet_NaN();
}

ImageError& ImageError::operator+=(const ImageError& other) {
  squaredMasked += other.squaredMasked;
  squaredFull += other.squaredFull;
  squaredBand += other.squaredBand;
  valuesMasked += other.valuesMasked;
  valuesFull += other.valuesFull;
  valuesBand += other.valuesBand;
  return *this;
}

nlohmann::json ImageError::json() const {
  return {{"mse_masked", number(mseMasked())}, {"psnr_masked_db", number(psnrDb(mseMasked()))},
          {"mse_full", number(mseFull())},     {"psnr_full_db", number(psnrDb(mseFull()))},
          {"mse_band", number(mseBand())},     {"psnr_band_db", number(psnrDb(mseBand()))}};
}

ImageError compareImages(const io::Image& predicted, const io::Image& truth,
                         const std::vector<uint8_t>* band) {
  if (predicted.width != truth.width || predicted.height != truth.height || predicted.channelCount() != 4 ||
      truth.channelCount() != 4)
    throw std::invalid_argument("compareImages: the images are not RGBA of the same size");
  const size_t n = size_t(truth.width) * truth.height;
  if (band && band->size() != n)
    throw std::invalid_argument("compareImages: the band is not the images' size");
  ImageError e;
  for (size_t p = 0; p < n; ++p) {
    const bool smoke = truth.pixels[p * 4 + 3] > 0.01f, inBand = smoke && band && (*band)[p];
    for (int c = 0; c < 3; ++c) {
      const double d =
          double(clipped(predicted.pixels[p * 4 + c])) - double(clipped(truth.pixels[p * 4 + c]));
      e.squaredFull += d * d;
      ++e.valuesFull;
      if (!smoke) continue;
      e.squaredMasked += d * d;
      ++e.valuesMasked;
      if (!inBand) continue;
      e.squaredBand += d * d;
      ++e.valuesBand;
    }
  }
  return e;
}

}  // namespace sixway::metrics
