// The frame-to-frame change of `sixway eval --scene` (eval/temporal_change.h) against sums worked by hand:
// which pixels count (the truth's alpha > 0.01 in either frame), clipping to [0, 1], the RMS and mean
// absolute change, and the truth's noise taken out in quadrature.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "eval/temporal_change.h"

namespace sixway::test {
namespace {

// A 3×1 RGBA image: every pixel grey `value` (R = G = B) with the given alpha.
io::Image row(float a, float b, float c, float alphaA, float alphaB, float alphaC) {
  io::Image image(3, 1, {"R", "G", "B", "A"});
  const float values[3] = {a, b, c}, alphas[3] = {alphaA, alphaB, alphaC};
  for (int x = 0; x < 3; ++x) {
    for (int ch = 0; ch < 3; ++ch) image.at(x, 0, ch) = values[x];
    image.at(x, 0, 3) = alphas[x];
  }
  return image;
}

TEST(TemporalChangeTest, CountsThePixelsWhereTheTruthHasSmokeInEitherFrame) {
  // Pixel 0: smoke in the previous truth only; pixel 1: in the current only; pixel 2: in neither (skipped,
  // although it changes most). The change is clipped: 1.4 reads as 1.
  const io::Image truthPrevious = row(0, 0, 0, 0.5f, 0.0f, 0.0f),
                  truthCurrent = row(0, 0, 0, 0.0f, 0.2f, 0.01f);
  const io::Image previous = row(0.2f, 0.5f, 0.0f, 1, 1, 1), current = row(0.5f, 1.4f, 1.0f, 1, 1, 1);
  eval::TemporalChange change;
  change.add(previous, current, truthPrevious, truthCurrent);
  EXPECT_EQ(change.values, 6u);
  EXPECT_NEAR(change.meanAbsolute(), (0.3 + 0.5) / 2, 1e-6);
  EXPECT_NEAR(change.rms(), std::sqrt((0.09 + 0.25) / 2), 1e-6);
  // A second pair pools with the first: every value weighs the same.
  change.add(current, current, truthPrevious, truthCurrent);
  EXPECT_EQ(change.values, 12u);
  EXPECT_NEAR(change.rms(), std::sqrt((0.09 + 0.25) / 4), 1e-6);
}

TEST(TemporalChangeTest, TakesTheNoiseOutInQuadrature) {
  eval::TemporalChange raw, noise;
  raw.squared = 25 * 3, raw.values = 3;     // RMS 5
  noise.squared = 9 * 2, noise.values = 2;  // RMS 3
  EXPECT_NEAR(eval::rmsWithoutNoise(raw, noise), 4.0, 1e-12);
  // Noise larger than the change: nothing is left, not an imaginary number.
  EXPECT_EQ(eval::rmsWithoutNoise(noise, raw), 0.0);
  EXPECT_TRUE(std::isnan(eval::rmsWithoutNoise(raw, eval::TemporalChange{})));
}

TEST(TemporalChangeTest, NothingComparedIsNullNotZero) {
  const eval::TemporalChange empty;
  EXPECT_TRUE(std::isnan(empty.rms()));
  EXPECT_TRUE(eval::temporalJson(empty)["rms"].is_null());
  EXPECT_TRUE(eval::temporalJson(empty)["mean_abs"].is_null());
}

TEST(TemporalChangeTest, RefusesFramesOfAnotherShape) {
  eval::TemporalChange change;
  const io::Image a = row(0, 0, 0, 1, 1, 1);
  io::Image rgb(3, 1, {"R", "G", "B"}), wide(4, 1, {"R", "G", "B", "A"});
  EXPECT_THROW(change.add(a, rgb, a, a), std::invalid_argument);
  EXPECT_THROW(change.add(a, a, a, wide), std::invalid_argument);
  EXPECT_EQ(change.values, 0u);
}

}  // namespace
}  // namespace sixway::test
