// The pixels `sixway render` counts as faults (metrics::imageFaults): not finite, negative, and a dark dot
// (up to 5 × 5 pixels) in lit smoke, but not a dark pixel of the background or a dark edge.
#include <gtest/gtest.h>

#include <limits>

#include "metrics/image_metrics.h"

namespace sixway::test {
namespace {

io::Image grey(float value) {
  io::Image image(16, 12, {"R", "G", "B", "A"});
  for (size_t p = 0; p < size_t(16 * 12); ++p) {
    for (int c = 0; c < 3; ++c) image.pixels[p * 4 + c] = value;
    image.pixels[p * 4 + 3] = 1.0f;
  }
  return image;
}

TEST(ImageFaultsTest, DarkPixelInLitSmoke) {
  io::Image lit = grey(0.4f);
  EXPECT_EQ(metrics::imageFaults(lit).total(), 0u);
  for (int c = 0; c < 3; ++c) lit.at(5, 6, c) = 0.0f;
  const metrics::ImageFaults f = metrics::imageFaults(lit);
  EXPECT_EQ(f.darkDots, 1u);
  EXPECT_EQ(f.notFinite + f.negative, 0u);
}

TEST(ImageFaultsTest, DarkDotOfFiveByFour) {
  io::Image lit = grey(0.4f);
  for (int y = 4; y < 8; ++y)
    for (int x = 5; x < 10; ++x)
      for (int c = 0; c < 3; ++c) lit.at(x, y, c) = 0.02f;
  // Counted are the pixels whose ring four pixels out clears the dot: x 6 to 8, y 4 to 7.
  EXPECT_EQ(metrics::imageFaults(lit).darkDots, 12u);
}

TEST(ImageFaultsTest, DarkBackgroundAndEdgesAreNoFaults) {
  io::Image image = grey(0.02f);  // the background
  for (int c = 0; c < 3; ++c) image.at(5, 6, c) = 0.0f;
  for (int y = 0; y < 12; ++y)  // a lit half with a dark column at its edge
    for (int x = 9; x < 16; ++x)
      for (int c = 0; c < 3; ++c) image.at(x, y, c) = 0.5f;
  EXPECT_EQ(metrics::imageFaults(image).total(), 0u);
}

TEST(ImageFaultsTest, NotFiniteAndNegative) {
  io::Image image = grey(0.3f);
  image.at(1, 1, 0) = std::numeric_limits<float>::quiet_NaN();
  image.at(2, 1, 3) = std::numeric_limits<float>::infinity();
  image.at(3, 1, 2) = -0.01f;
  const metrics::ImageFaults f = metrics::imageFaults(image);
  EXPECT_EQ(f.notFinite, 2u);
  EXPECT_EQ(f.negative, 1u);
}

}  // namespace
}  // namespace sixway::test
