// The six-way ceiling (six_way_fit.h, fitted_lightmaps.h): the blend's weights, the non-negative
// least-squares fit against its optimality conditions, the baker under lights from any direction against the
// CPU oracle, and the fitted lightmaps against the axis-lit ones where the fit's directions are the axes.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <random>

#include "cpu_reference.h"
#include "image_stats.h"
#include "io/error.h"
#include "reference/fitted_lightmaps.h"
#include "reference/lightmap_baker.h"
#include "render/sixway.h"
#include "test_volumes.h"

namespace sixway::test {
namespace {

TEST(SixWayWeights, AreTheSquaredComponentsOnTheSideTheLightIsOn) {
  const std::array<float, 6> right = reference::sixWayWeights({1, 0, 0});
  EXPECT_EQ(right, (std::array<float, 6>{1, 0, 0, 0, 0, 0}));
  const std::array<float, 6> front = reference::sixWayWeights({0, 0, -1});
  EXPECT_EQ(front, (std::array<float, 6>{0, 0, 0, 0, 0, 1}));
  const glm::vec3 d = glm::normalize(glm::vec3(-1, 2, 0.5f));
  const std::array<float, 6> w = reference::sixWayWeights(d);
  EXPECT_FLOAT_EQ(w[1], d.x * d.x);  // Left
  EXPECT_FLOAT_EQ(w[2], d.y * d.y);  // Top
  EXPECT_FLOAT_EQ(w[4], d.z * d.z);  // Back
  EXPECT_EQ(w[0] + w[3] + w[5], 0.0f);
  EXPECT_NEAR(w[1] + w[2] + w[4], 1.0f, 1e-6f);
}

TEST(SphereDirections, AreUnitAndBalanced) {
  const std::vector<glm::vec3> d = reference::sphereDirections(36);
  ASSERT_EQ(d.size(), 36u);
  glm::vec3 sum(0);
  for (const glm::vec3& v : d) {
    EXPECT_NEAR(glm::length(v), 1.0f, 1e-5f);
    sum += v;
  }
  EXPECT_LT(glm::length(sum) / 36.0f, 0.05f);
  EXPECT_THROW(reference::fitDirections(31), io::InputError);
  EXPECT_THROW(reference::fitDirections(6), io::InputError);
  EXPECT_EQ(reference::fitDirections(12).size(), 12u);
}

// The fitted m against the Karush–Kuhn–Tucker conditions of min |W m − r|², m ≥ 0, which hold at the optimum
// and only there (the problem is convex): m ≥ 0; the gradient Wᵀ(W m − r) zero where m > 0, ≥ 0 where m = 0.
void expectOptimal(const reference::SixWayFit& fit, const std::vector<float>& values) {
  const std::array<float, 6> m = fit.fit(values);
  std::array<double, 6> gradient{};
  double scale = 0;
  for (size_t j = 0; j < values.size(); ++j) {
    const std::array<float, 6> w = reference::sixWayWeights(fit.directions()[j]);
    double blend = 0;
    for (int i = 0; i < 6; ++i) blend += double(w[i]) * m[i];
    for (int i = 0; i < 6; ++i) gradient[i] += w[i] * (blend - values[j]);
    scale = std::max(scale, std::abs(double(values[j])));
  }
  for (int i = 0; i < 6; ++i) {
    EXPECT_GE(m[i], 0.0f) << "channel " << i;
    if (m[i] > 0)
      EXPECT_NEAR(gradient[i], 0.0, 1e-4 * scale) << "channel " << i;
    else
      EXPECT_GE(gradient[i], -1e-4 * scale) << "channel " << i;
  }
}

TEST(SixWayFit, RecoversTheMapsOfASixWayMaterial) {
  const reference::SixWayFit fit(reference::sphereDirections(36));
  const std::array<float, 6> maps = {0.7f, 0.1f, 0.4f, 0.0f, 1.3f, 0.25f};
  std::vector<float> values;
  for (const glm::vec3& d : fit.directions()) {
    const std::array<float, 6> w = reference::sixWayWeights(d);
    float v = 0;
    for (int i = 0; i < 6; ++i) v += w[i] * maps[i];
    values.push_back(v);
  }
  const std::array<float, 6> m = fit.fit(values);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(m[i], maps[i], 1e-5f) << "channel " << i;
}

// Values no six-way material gives, many with an unconstrained optimum below 0 in some channel.
TEST(SixWayFit, IsTheNonNegativeLeastSquaresOptimum) {
  const reference::SixWayFit fit(reference::sphereDirections(24));
  std::mt19937 random(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  int clamped = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<float> values;
    for (const glm::vec3& d : fit.directions())  // a light spot toward a random side, plus noise
      values.push_back(std::max(0.0f, std::pow(std::max(0.0f, d.x * (trial % 3 - 1.0f) + d.y * 0.3f), 3.0f) +
                                          0.2f * uniform(random) - 0.05f));
    expectOptimal(fit, values);
    const std::array<float, 6> m = fit.fit(values);
    clamped += std::count(m.begin(), m.end(), 0.0f) > 0;
  }
  EXPECT_GT(clamped, 20) << "the trials must exercise the non-negativity";
  EXPECT_THROW(fit.fit(std::vector<float>(5, 1.0f)), std::invalid_argument);
}

TEST(SixWayFit, RefusesDirectionsThatLeaveAChannelUnlit) {
  std::vector<glm::vec3> upper;  // no light from the front half (z < 0): Front is never lit
  for (const glm::vec3& d : reference::sphereDirections(48))
    if (d.z > 0) upper.push_back(d);
  EXPECT_THROW(reference::SixWayFit{upper}, std::invalid_argument);
}

class FittedLightmapsTest : public RenderTest {
 protected:
  CpuVolume cpuVolume_ = puffs(16);
  render::DeviceVolume volume_ = upload(cpuVolume_);
  render::Camera camera_ = obliqueCamera();
  render::ImagePlane billboard_ = squareBillboard(camera_, cpuVolume_.box());
};

// Lights from oblique directions (none along a camera or volume axis), baked on the GPU and marched directly
// toward each light on the CPU: the same 2 % bound as the axis lights' (test_baker.cpp).
TEST_F(FittedLightmapsTest, TheBakerTakesLightsFromAnyDirection) {
  std::array<glm::vec3, 6> lights;
  const std::vector<glm::vec3> d = reference::sphereDirections(6);
  for (int i = 0; i < 6; ++i) lights[i] = glm::normalize(d[i] + glm::vec3(0.1f, -0.2f, 0.15f));
  reference::LightmapBaker baker(context(), pipelineCache());
  reference::BakeSettings settings;
  settings.width = settings.height = 24;
  settings.lights = lights;
  const scene::Smoke smoke = puffOptics();
  const io::Image gpu = baker.bake(volume_.view(), smoke, camera_, billboard_, settings);
  const io::Image cpu = bakeSixWay(cpuVolume_, smoke, camera_, billboard_, 24, 24, 0.25, &lights);
  const auto errors = channelErrors(gpu, cpu);
  for (int c = 0; c < render::kSixWayLights; ++c) {
    EXPECT_GT(errors[c].maxRef, 0.02) << c << ": the light must reach the smoke";
    EXPECT_LT(errors[c].maxAbs, 0.02 * errors[c].maxRef) << "light " << c;
  }
  settings.lights->at(2) = glm::vec3(0.0f, 2.0f, 0.0f);
  EXPECT_THROW(baker.bake(volume_.view(), smoke, camera_, billboard_, settings), std::invalid_argument);
}

// With the six axes (shuffled) as the fit's directions, every channel is lit by its own light alone: the
// fitted maps are the axis-lit maps (up to the higher orders' noise and the light grids' orientation), each
// in its own channel — where the Right and Left channels differ by far more than that.
TEST_F(FittedLightmapsTest, OnTheSixAxesTheFitIsTheAxisLitMaps) {
  const std::vector<glm::vec3> axes = {{0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0, -1}, {0, 1, 0}};
  reference::FittedLightmaps fitted(context(), pipelineCache(), axes);
  reference::ScatteredLightmaps scattered(context(), pipelineCache());
  reference::BakeSettings settings;
  settings.width = settings.height = 16;
  reference::MultipleScattering multiple;
  multiple.samples = 256;
  const scene::Smoke smoke = puffOptics();
  const io::Image fit = fitted.bake(volume_.view(), smoke, camera_, billboard_, settings, multiple);
  const io::Image axis = scattered.bake(volume_.view(), smoke, camera_, billboard_, settings,
                                        reference::Scattering::Multiple, multiple);
  const auto errors = channelErrors(fit, axis);
  for (int c = 0; c < render::kSixWayChannels; ++c) {
    EXPECT_GT(errors[c].maxRef, 0.02) << fit.channels[c];
    EXPECT_LT(errors[c].rms, 0.03 * errors[c].maxRef) << fit.channels[c];
  }
  io::Image swapped = axis;  // Right and Left exchanged
  for (size_t p = 0; p < size_t(16 * 16); ++p)
    std::swap(swapped.pixels[p * 8 + 0], swapped.pixels[p * 8 + 1]);
  const auto apart = channelErrors(swapped, axis);
  EXPECT_GT(apart[0].rms, 0.1 * apart[0].maxRef) << "Right and Left must differ for the test to see a swap";
  EXPECT_FALSE(fitted.stageTimes().empty());
  EXPECT_THROW(reference::FittedLightmaps(context(), pipelineCache(),
                                          std::vector<glm::vec3>(axes.begin(), axes.begin() + 4)),
               std::invalid_argument);
}

}  // namespace
}  // namespace sixway::test
