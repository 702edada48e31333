#include "image_stats.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sixway::test {

std::vector<ChannelError> channelErrors(const io::Image& a, const io::Image& b) {
  if (a.width != b.width || a.height != b.height || a.channelCount() != b.channelCount())
    throw std::invalid_argument("channelErrors: images of different shapes");
  std::vector<ChannelError> errors(a.channelCount());
  const size_t pixels = size_t(a.width) * a.height;
  for (size_t i = 0; i < pixels; ++i)
    for (int c = 0; c < a.channelCount(); ++c) {
      const double d = double(a.pixels[i * a.channelCount() + c]) - b.pixels[i * b.channelCount() + c];
      errors[c].maxAbs = std::max(errors[c].maxAbs, std::fabs(d));
      errors[c].rms += d * d;
      errors[c].maxRef = std::max(errors[c].maxRef, double(std::fabs(b.pixels[i * b.channelCount() + c])));
    }
  for (ChannelError& e : errors) e.rms = std::sqrt(e.rms / double(pixels));
  return errors;
}

io::Image channel(const io::Image& image, int c) {
  io::Image one(image.width, image.height, {image.channels[c]});
  for (size_t i = 0; i < size_t(image.width) * image.height; ++i)
    one.pixels[i] = image.pixels[i * image.channelCount() + c];
  return one;
}

double peak(const io::Image& image, int c) {
  double m = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) m = std::max(m, double(image.at(x, y, c)));
  return m;
}

double rms(const io::Image& a, const io::Image& b, const std::vector<int>& channels) {
  double sum = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int c : channels) sum += std::pow(double(a.at(x, y, c)) - b.at(x, y, c), 2);
  return std::sqrt(sum / (double(a.width) * a.height * channels.size()));
}

TwoSeeds meanOfTwoSeeds(const io::Image& a, const io::Image& b, const std::vector<int>& channels) {
  TwoSeeds r{a, rms(a, b, channels) / 2};
  for (size_t i = 0; i < a.pixels.size(); ++i) r.mean.pixels[i] = 0.5f * (a.pixels[i] + b.pixels[i]);
  return r;
}

}  // namespace sixway::test
