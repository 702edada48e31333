#include "eval/temporal_change.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sixway::eval {
namespace {

float clipped(float v) {
  return std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
}

bool sameRgba(const io::Image& a, const io::Image& b) {
  return a.width == b.width && a.height == b.height && a.channelCount() == 4 && b.channelCount() == 4;
}

nlohmann::json number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

}  // namespace

void TemporalChange::add(const io::Image& previous, const io::Image& current, const io::Image& truthPrevious,
                         const io::Image& truthCurrent) {
  if (!sameRgba(previous, current) || !sameRgba(previous, truthPrevious) || !sameRgba(previous, truthCurrent))
    throw std::invalid_argument("TemporalChange: the frames are not RGBA of one size");
  for (size_t p = 0, n = size_t(current.width) * current.height; p < n; ++p) {
    if (!(truthPrevious.pixels[p * 4 + 3] > 0.01f || truthCurrent.pixels[p * 4 + 3] > 0.01f)) continue;
    for (int c = 0; c < 3; ++c) {
      const double d =
          double(clipped(current.pixels[p * 4 + c])) - double(clipped(previous.pixels[p * 4 + c]));
      absolute += std::abs(d);
      squared += d * d;
      ++values;
    }
  }
}

double TemporalChange::meanAbsolute() const {
  return values ? absolute / double(values) : std::numeric_limits<double>::quiet_NaN();
}

double TemporalChange::rms() const {
  return values ? std::sqrt(squared / double(values)) : std::numeric_limits<double>::quiet_NaN();
}

double rmsWithoutNoise(const TemporalChange& raw, const TemporalChange& noise) {
  const double r = raw.rms(), n = noise.rms();
  if (std::isnan(r) || std::isnan(n)) return std::numeric_limits<double>::quiet_NaN();
  return std::sqrt(std::max(0.0, r * r - n * n));
}

nlohmann::json temporalJson(const TemporalChange& change) {
  return {{"mean_abs", number(change.meanAbsolute())}, {"rms", number(change.rms())}};
}

}  // namespace sixway::eval
