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

}  // namespace sixway::test
