#include "eval/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sixway::eval {
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

}  // namespace sixway::eval
