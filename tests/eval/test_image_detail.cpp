// The detail figure of `sixway eval --scene` (eval/image_detail.h): a blurred picture holds less high-pass
// energy than the sharp one, a flat one none, and the truth's Monte Carlo noise comes out of two noisy
// renders.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "eval/image_detail.h"

namespace sixway::test {
namespace {

constexpr int kSize = 96;

// A grey RGBA picture of luminance f(x, y), alpha 1.
io::Image picture(const std::function<float(int, int)>& f) {
  io::Image image(kSize, kSize, {"R", "G", "B", "A"});
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      for (int c = 0; c < 3; ++c) image.at(x, y, c) = f(x, y);
      image.at(x, y, 3) = 1.0f;
    }
  return image;
}

// Wisps: a sum of sines of periods 3 to 24 pixels around a mid grey.
float wisps(int x, int y) {
  float v = 0.5f;
  for (int k = 0; k < 6; ++k) {
    const float period = 3.0f * float(1 << (k / 2)) * (k % 2 ? 1.5f : 1.0f);
    v += 0.06f * std::sin(6.2831853f * (x * (k % 3 + 1) + y * (3 - k % 3)) / (3.0f * period));
  }
  return v;
}

TEST(ImageDetailTest, BlurLosesDetailAndFlatHasNone) {
  const std::vector<uint8_t> all(size_t(kSize) * kSize, 1);
  const io::Image sharp = picture(wisps);
  // A box blur of 5 × 5 pixels, as a 64² lightmap stretched over a larger frame would be.
  const io::Image blurred = picture([&](int x, int y) {
    float s = 0;
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx)
        s += wisps(std::clamp(x + dx, 0, kSize - 1), std::clamp(y + dy, 0, kSize - 1));
    return s / 25;
  });
  const double e = eval::highPassEnergy(sharp, all);
  EXPECT_GT(e, 1.0);
  EXPECT_LT(eval::highPassEnergy(blurred, all), 0.5 * e);
  EXPECT_EQ(eval::highPassEnergy(picture([](int, int) { return 0.3f; }), all), 0.0);
  std::vector<uint8_t> none(all.size(), 0);
  EXPECT_EQ(eval::highPassEnergy(sharp, none), 0.0);
}

TEST(ImageDetailTest, TwoNoisyRendersGiveTheNoiseFreeEnergy) {
  const std::vector<uint8_t> all(size_t(kSize) * kSize, 1);
  std::mt19937 rng(3);
  std::normal_distribution<float> noise(0.0f, 0.08f);
  const auto noisy = [&] { return picture([&](int x, int y) { return wisps(x, y) + noise(rng); }); };
  const io::Image a = noisy(), b = noisy();
  const double clean = eval::highPassEnergy(picture(wisps), all);
  const double raw = eval::highPassEnergy(a, all);
  EXPECT_GT(raw, 1.3 * clean) << "the noise must matter for the test to mean something";
  const double corrected = raw - 0.5 * eval::highPassEnergyOfDifference(a, b, all);
  EXPECT_NEAR(corrected, clean, 0.05 * clean);
}

TEST(ImageDetailTest, MaskIsTheTruthsSmoke) {
  io::Image truth = picture(wisps);
  truth.at(3, 4, 3) = 0.005f;
  const std::vector<uint8_t> mask = eval::smokeMask(truth);
  EXPECT_EQ(mask[size_t(4) * kSize + 3], 0);
  EXPECT_EQ(mask[size_t(4) * kSize + 4], 1);
}

}  // namespace
}  // namespace sixway::test
