// Multiple-scattering six-way lightmaps (scattered_lightmaps.h): the path tracer's lowest recorded order,
// the alpha-guided upsampling on the CPU, energy (albedo 0 gives no multiple scattering; multiple ≥
// single everywhere), and the fast split (exact single scattering + orders ≥ 2 at half resolution) against
// a high-sample all-orders trace.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numeric>

#include "io/error.h"
#include "reference/path_tracer.h"
#include "reference/scattered_lightmaps.h"
#include "render/sixway.h"
#include "test_volumes.h"

namespace sixway::test {
namespace {

class ScatteredLightmapsTest : public RenderTest {
 protected:
  void SetUp() override { settings_.width = settings_.height = 32; }
  io::Image bake(reference::Scattering scattering, const reference::MultipleScattering& multiple = {},
                 scene::Smoke smoke = puffOptics()) {
    return lightmaps_.bake(volume_.view(), smoke, camera_, billboard_, settings_, scattering, multiple);
  }
  CpuVolume cpuVolume_ = puffs(16);
  render::DeviceVolume volume_ = upload(cpuVolume_);
  render::Camera camera_ = obliqueCamera();
  render::ImagePlane billboard_ = squareBillboard(camera_, cpuVolume_.box());
  reference::BakeSettings settings_;
  reference::ScatteredLightmaps lightmaps_{context(), pipelineCache()};
};

// RMS over the pixels of channels [first, last).
double channelRms(const io::Image& a, const io::Image& b, int first, int last) {
  double sum = 0;
  for (size_t p = 0; p < size_t(a.width) * a.height; ++p)
    for (int c = first; c < last; ++c) sum += std::pow(double(a.pixels[p * 8 + c]) - b.pixels[p * 8 + c], 2);
  return std::sqrt(sum / (double(a.width) * a.height * (last - first)));
}
double lightRms(const io::Image& a, const io::Image& b) {
  return channelRms(a, b, 0, render::kSixWayLights);
}
double emissionRms(const io::Image& a, const io::Image& b) {
  return channelRms(a, b, render::Emissive, render::Emissive + 1);
}

TEST_F(ScatteredLightmapsTest, TracingFromOrderTwoWithOneOrderIsBlackWithTheSameAlpha) {
  reference::PathTracer tracer(context(), pipelineCache());
  reference::TraceSettings s;
  s.width = s.height = 16;
  s.maxOrders = 1;
  tracer.beginSixWay(volume_.view(), puffOptics(), camera_, billboard_, s);
  tracer.accumulate(8);
  const io::Image all = tracer.image();
  s.minOrder = 2;
  tracer.beginSixWay(volume_.view(), puffOptics(), camera_, billboard_, s);
  tracer.accumulate(8);
  const io::Image higher = tracer.image();
  double alpha = 0;
  for (size_t p = 0; p < size_t(16 * 16); ++p) {
    for (int c = 0; c < render::kSixWayLights; ++c) ASSERT_EQ(higher.pixels[p * 8 + c], 0.0f) << p;
    ASSERT_EQ(higher.pixels[p * 8 + 6], all.pixels[p * 8 + 6]) << "alpha of pixel " << p;
    alpha += all.pixels[p * 8 + 6];
  }
  EXPECT_GT(alpha, 10.0) << "the volume is not in view";
  s.minOrder = 0;
  EXPECT_THROW(tracer.beginSixWay(volume_.view(), puffOptics(), camera_, billboard_, s), io::InputError);
}

TEST(UpsampleAlphaGuided, KeepsTheLightPerOpacityAndLeavesEmptyPixelsDark) {
  // Low: 2×2 pixels of light 0.5·α (c = 0..5) and alpha 0.8; full: 4×4 with alpha varying, one pixel 0.
  io::Image low(2, 2, {"r", "l", "t", "b", "k", "f", "a", "e"}), full(4, 4, low.channels);
  for (size_t p = 0; p < 4; ++p) {
    for (int c = 0; c < 6; ++c) low.pixels[p * 8 + c] = 0.4f;
    low.pixels[p * 8 + 6] = 0.8f;
  }
  for (size_t p = 0; p < 16; ++p) full.pixels[p * 8 + 6] = float(p) / 16.0f;
  const io::Image up = reference::upsampleAlphaGuided(low, full);
  for (size_t p = 0; p < 16; ++p) {
    for (int c = 0; c < 6; ++c) EXPECT_NEAR(up.pixels[p * 8 + c], 0.5f * float(p) / 16.0f, 1e-6f) << p;
    EXPECT_EQ(up.pixels[p * 8 + 6], 0.0f);
    EXPECT_EQ(up.pixels[p * 8 + 7], 0.0f);
  }
  // Downsample 1 with the same alpha is the identity; where the traced alpha is 0 nothing is added.
  io::Image same = low;
  same.pixels[6] = 0.0f;
  const io::Image identity = reference::upsampleAlphaGuided(same, same);
  for (int c = 0; c < 6; ++c) {
    EXPECT_EQ(identity.pixels[c], 0.0f);
    EXPECT_NEAR(identity.pixels[8 + c], 0.4f, 1e-6f);
  }
  EXPECT_THROW(reference::upsampleAlphaGuided(low, io::Image(5, 4, low.channels)), std::invalid_argument);
}

TEST_F(ScatteredLightmapsTest, AlbedoZeroHasNoMultipleScatteringAndMultipleOnlyAddsLight) {
  scene::Smoke black = puffOptics();
  black.albedo = 0.0f;
  const io::Image single = bake(reference::Scattering::Single, {}, black);
  EXPECT_EQ(bake(reference::Scattering::Multiple, {}, black).pixels, single.pixels);

  const io::Image ss = bake(reference::Scattering::Single), ms = bake(reference::Scattering::Multiple);
  double gain = 0, emissionGain = 0;
  for (size_t i = 0; i < ss.pixels.size(); ++i) {
    ASSERT_GE(ms.pixels[i], ss.pixels[i]) << i;
    if (i % 8 == 6) {
      ASSERT_EQ(ms.pixels[i], ss.pixels[i]) << "alpha is the baker's";
    }
    (i % 8 == 7 ? emissionGain : gain) += ms.pixels[i] - ss.pixels[i];
  }
  EXPECT_GT(gain, 0.1 * std::accumulate(ss.pixels.begin(), ss.pixels.end(), 0.0));
  EXPECT_GT(emissionGain, 0.0) << "the smoke scatters its own emission too";
}

// The split at half resolution and 64 samples against every order traced at full resolution with 1024
// samples. The reference has Monte Carlo noise of its own (measured from a second seed); what remains of
// the split's error beyond it is a fraction of the light single scattering misses.
TEST_F(ScatteredLightmapsTest, TheSplitMatchesTheAllOrdersTrace) {
  reference::MultipleScattering traced;
  traced.traceAllOrders = true;
  traced.samples = 1024;
  const io::Image truth = bake(reference::Scattering::Multiple, traced);
  traced.seed = 2;
  const io::Image second = bake(reference::Scattering::Multiple, traced);
  const double truthNoise = lightRms(truth, second) / std::sqrt(2.0);
  reference::MultipleScattering split;
  split.samples = 64;
  split.downsample = 2;  // through the upsampling
  const io::Image fast = bake(reference::Scattering::Multiple, split),
                  single = bake(reference::Scattering::Single);
  const double splitError = lightRms(fast, truth);
  const double singleError = lightRms(single, truth);

  // The emission, direct and scattered: the same split (exact direct part, traced scattered part).
  const double emissionNoise = emissionRms(truth, second) / std::sqrt(2.0);
  const double emissionSplit = emissionRms(fast, truth), emissionSingle = emissionRms(single, truth);
  const double emissionOwn =
      std::sqrt(std::max(0.0, emissionSplit * emissionSplit - emissionNoise * emissionNoise));
  RecordProperty("emission_split_rms", std::to_string(emissionSplit));
  RecordProperty("emission_single_rms", std::to_string(emissionSingle));
  RecordProperty("emission_truth_noise_rms", std::to_string(emissionNoise));
  std::printf("emission rms: split %.4g, direct only %.4g, truth noise %.4g\n", emissionSplit, emissionSingle,
              emissionNoise);
  EXPECT_GT(emissionSingle, 3.0 * emissionNoise) << "the direct emission misses the scattered";
  EXPECT_LT(emissionOwn, 0.25 * emissionSingle)
      << "split " << emissionSplit << ", truth noise " << emissionNoise;
  const double ownError = std::sqrt(std::max(0.0, splitError * splitError - truthNoise * truthNoise));
  RecordProperty("split_rms", std::to_string(splitError));
  RecordProperty("single_rms", std::to_string(singleError));
  RecordProperty("truth_noise_rms", std::to_string(truthNoise));
  EXPECT_GT(singleError, 3.0 * truthNoise) << "single scattering misses light the truth resolves";
  EXPECT_LT(ownError, 0.25 * singleError) << "split " << splitError << ", truth noise " << truthNoise;
}

}  // namespace
}  // namespace sixway::test
