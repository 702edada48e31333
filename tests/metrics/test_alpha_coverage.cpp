// The coverage `sixway render` reports of a frame (metrics::alphaCoverage): the share of pixels whose alpha
// reaches the threshold.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "metrics/image_metrics.h"

namespace sixway::test {
namespace {

TEST(AlphaCoverageTest, CountsThePixelsWithAlphaAtTheThreshold) {
  io::Image frame(4, 1, {"R", "G", "B", "A"});
  for (int x = 0; x < 4; ++x) frame.at(x, 0, 3) = std::vector<float>{0.0f, 0.05f, 0.1f, 1.0f}[x];
  EXPECT_DOUBLE_EQ(metrics::alphaCoverage(frame), 0.5);
  EXPECT_DOUBLE_EQ(metrics::alphaCoverage(frame, 0.01f), 0.75);
  EXPECT_THROW(metrics::alphaCoverage(io::Image(1, 1, {"R", "G", "B"})), std::invalid_argument);
}

}  // namespace
}  // namespace sixway::test
