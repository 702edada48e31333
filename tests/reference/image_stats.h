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

// The largest value of channel c.
double peak(const io::Image& image, int c);

// RMS of a − b over the pixels and the given channels.
double rms(const io::Image& a, const io::Image& b, const std::vector<int>& channels);

// The mean of two renders with independent seeds, and the Monte Carlo RMS error of that mean, estimated from
// their difference (each render's error is RMS(a − b)/√2, the mean's is half of RMS(a − b)).
struct TwoSeeds {
  io::Image mean;
  double noise;
};
TwoSeeds meanOfTwoSeeds(const io::Image& a, const io::Image& b, const std::vector<int>& channels);

}  // namespace sixway::test
