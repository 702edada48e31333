// eval::LightmapMetrics against PSNRs worked out by hand (docs/conventions.md, "Metrics"): linear values
// clipped to [0, 1], 10·log10(1 / MSE), masked to the pixels where the reference alpha > 0.01.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "eval/lightmap_metrics.h"

namespace sixway::test {
namespace {

// The inputs are floats: 0.6f − 0.5f is 0.1 only to about 1e-7 relative, a few 1e-6 dB.
constexpr double kDb = 1e-5;

// `pixels` pixels of eight channels, all `value`, alpha (channel 6) `alpha`.
std::vector<float> image(int pixels, float value, float alpha) {
  std::vector<float> v(size_t(pixels) * 8, value);
  for (int p = 0; p < pixels; ++p) v[size_t(p) * 8 + 6] = alpha;
  return v;
}

TEST(LightmapMetrics, AConstantErrorGivesItsPsnrAndTheMaskLeavesOutEmptyPixels) {
  std::vector<float> reference = image(4, 0.5f, 0.5f), predicted = image(4, 0.6f, 0.5f);
  // Pixels 2 and 3: empty in the reference, and predicted far off; only the full figure sees them.
  for (int p = 2; p < 4; ++p) {
    for (int c = 0; c < 8; ++c) reference[p * 8 + c] = 0.0f, predicted[p * 8 + c] = 0.3f;
  }
  eval::LightmapMetrics m;
  m.add(predicted, reference);
  const nlohmann::json s = m.summary();
  // Masked: 7 channels off by 0.1, alpha exact → MSE = 7/8 · 0.01.
  EXPECT_NEAR(s["psnr_masked_db"].get<double>(), 10 * std::log10(1 / (0.875 * 0.01)), kDb);
  // Full: half the pixels as above, half off by 0.3 in every channel.
  EXPECT_NEAR(s["psnr_full_db"].get<double>(), 10 * std::log10(1 / (0.5 * 0.875 * 0.01 + 0.5 * 0.09)), kDb);
  EXPECT_NEAR(s["pairs_psnr_masked_db"]["right_left"].get<double>(), 20.0, kDb);
  EXPECT_NEAR(s["pairs_psnr_masked_db"]["alpha_emissive"].get<double>(), 10 * std::log10(1 / 0.005), kDb);
  EXPECT_NEAR(s["channels_psnr_masked_db"]["Right"].get<double>(), 20.0, kDb);
  EXPECT_NEAR(s["channels_psnr_masked_db"]["emissive"].get<double>(), 20.0, kDb);
  EXPECT_TRUE(s["channels_psnr_masked_db"]["alpha"].is_null()) << "exact: no finite PSNR";
}

TEST(LightmapMetrics, ValuesAreClippedToTheUnitRangeAndNanCountsAsZero) {
  const std::vector<float> reference = image(1, 1.0f, 1.0f);
  std::vector<float> predicted = image(1, 7.0f, 1.0f);  // over-bright: clipped to 1, no error
  predicted[0] = NAN;                                   // NaN: 0, an error of 1 in one channel of eight
  eval::LightmapMetrics m;
  m.add(predicted, reference);
  EXPECT_NEAR(m.summary()["psnr_masked_db"].get<double>(), 10 * std::log10(8.0), kDb);
}

TEST(LightmapMetrics, PoolsPixelsAcrossSamplesAndAveragesSamplePsnrs) {
  eval::LightmapMetrics m;
  m.add(image(1, 0.6f, 1.0f), image(1, 0.5f, 1.0f));  // 7 of 8 channels off by 0.1 (alpha exact)
  m.add(image(1, 0.5f, 1.0f), image(1, 0.5f, 1.0f));  // exact: counted as 100 dB in the mean
  const nlohmann::json s = m.summary();
  const double first = 10 * std::log10(1 / (7.0 / 8.0 * 0.01));
  EXPECT_NEAR(s["psnr_masked_db"].get<double>(), 10 * std::log10(1 / (7.0 / 16.0 * 0.01)), kDb);
  EXPECT_NEAR(s["mean_sample_psnr_masked_db"].get<double>(), 0.5 * (first + 100.0), kDb);
  EXPECT_EQ(s["samples"].get<int>(), 2);
}

}  // namespace
}  // namespace sixway::test
