#pragma once
// Per-channel differences between two images of the same shape, for tolerances stated per channel.
#include <string>
#include <vector>

#include "io/image.h"

namespace sixway::test {

struct ChannelError {
  double maxAbs = 0;  // largest |a − b|
  double rms = 0;     // root mean square of a − b
  double maxRef = 0;  // largest |b|, to state tolerances relative to the signal
};

// Throws std::invalid_argument when the shapes differ.
std::vector<ChannelError> channelErrors(const io::Image& a, const io::Image& b);

// One channel of an image as a one-channel image.
io::Image channel(const io::Image& image, int c);

}  // namespace sixway::test
