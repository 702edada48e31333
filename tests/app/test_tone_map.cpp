// The display transform of rendered PNGs (app/tone_map.h) against Narkowicz's published curve (2016): its
// values at 0, 1 and large inputs, monotonicity, the exposure in stops, and the clamp that stays the default.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "app/tone_map.h"

namespace sixway::test {
namespace {

// The rational fit evaluated in double precision, independently of the float implementation.
double narkowicz(double x) {
  return std::min(1.0, x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14));
}

TEST(ToneMapTest, AcesFitFollowsThePublishedCurve) {
  EXPECT_EQ(app::acesFitted(0.0f), 0.0f);
  EXPECT_EQ(app::acesFitted(-3.0f), 0.0f) << "negative light is black, not a negative value";
  EXPECT_NEAR(app::acesFitted(1.0f), 0.8038, 1e-4) << "1 maps to about 0.8 (the fit is pre-exposed)";
  EXPECT_EQ(app::acesFitted(1e6f), 1.0f);
  float previous = 0.0f;
  for (int i = 1; i <= 4000; ++i) {
    const float x = float(i) / 400.0f;
    EXPECT_NEAR(app::acesFitted(x), narkowicz(x), 1e-6) << x;
    EXPECT_GE(app::acesFitted(x), previous) << "monotone at " << x;
    previous = app::acesFitted(x);
  }
}

TEST(ToneMapTest, ExposureInStopsThenTheCurveOrTheClamp) {
  io::Image frame(2, 1, {"R", "G", "B", "A"});
  frame.pixels = {0.25f, 0.5f, 2.0f, 1.0f, 0.0f, 0.1f, 0.4f, 0.0f};
  const io::Image clamped = app::toDisplay(frame, {scene::ToneMap::Clamp, 1.0f});
  ASSERT_EQ(clamped.channels, (std::vector<std::string>{"R", "G", "B"})) << "alpha is not displayed";
  EXPECT_FLOAT_EQ(clamped.at(0, 0, 0), 0.5f);
  EXPECT_FLOAT_EQ(clamped.at(0, 0, 1), 1.0f);
  EXPECT_FLOAT_EQ(clamped.at(0, 0, 2), 1.0f);
  EXPECT_FLOAT_EQ(clamped.at(1, 0, 2), 0.8f);
  const io::Image filmic = app::toDisplay(frame, {scene::ToneMap::Aces, -1.0f});
  EXPECT_NEAR(filmic.at(0, 0, 2), narkowicz(1.0), 1e-6);
  EXPECT_NEAR(filmic.at(1, 0, 1), narkowicz(0.05), 1e-6);
  const io::Image same = app::toDisplay(frame, {});
  EXPECT_FLOAT_EQ(same.at(1, 0, 2), 0.4f) << "the default transform is the clamp at exposure 0";
}

}  // namespace
}  // namespace sixway::test
