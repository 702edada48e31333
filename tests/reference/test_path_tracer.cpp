// The volumetric path tracer (majorant.comp, path_trace.comp): exact answers and energy conservation,
// convergence to the baker as 1/√spp, and single scattering of a point light and of an environment
// against the CPU oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <numeric>

#include "cpu_reference.h"
#include "image_stats.h"
#include "reference/lightmap_baker.h"
#include "reference/path_tracer.h"
#include "render/sixway.h"
#include "test_volumes.h"

namespace sixway::test {
namespace {

class PathTracerTest : public RenderTest {
 protected:
  // An RGB + alpha image of `volume` with the oblique camera, pixel centres, no lights unless given.
  io::Image traceImage(const CpuVolume& volume, const scene::Smoke& smoke, reference::TraceSettings settings,
                       uint32_t samples, const std::vector<scene::Light>& lights = {}) {
    const render::DeviceVolume device = upload(volume);
    const render::Camera camera = obliqueCamera();
    tracer_.beginImage(device.view(), smoke, camera, squareBillboard(camera, volume.box()), lights, settings);
    tracer_.accumulate(samples);
    return tracer_.image();
  }
  reference::PathTracer tracer_{context(), pipelineCache()};
};

reference::TraceSettings settings(int size, int maxOrders) {
  reference::TraceSettings s;
  s.width = s.height = size;
  s.maxOrders = maxOrders;
  s.jitter = false;
  s.samplesPerPass = 16;
  return s;
}

TEST_F(PathTracerTest, EmptyVolumeIsBlackWithAlphaZero) {
  const CpuVolume empty = constantBox({8, 8, 8}, 0.125f, 0.0f);
  const scene::Light sun{scene::DirectionalLight{{0.0f, 1.0f, 0.0f}}};
  for (float v : traceImage(empty, puffOptics(), settings(16, 8), 16, {sun}).pixels) ASSERT_EQ(v, 0.0f);
  const render::DeviceVolume device = upload(empty);
  const render::Camera camera = obliqueCamera();
  tracer_.beginSixWay(device.view(), puffOptics(), camera, squareBillboard(camera, empty.box()),
                      settings(16, 8));
  tracer_.accumulate(16);
  for (float v : tracer_.image().pixels) ASSERT_EQ(v, 0.0f);
}

// A non-scattering box of constant density in front of a coloured background: alpha = 1 − exp(−τ) and the
// radiance is the background times exp(−τ), with τ from the analytic chord. With the majorant equal to the
// density, each sample is 0 or 1, so the tolerance is binomial: 5 standard deviations of the mean.
TEST_F(PathTracerTest, AbsorbingBoxGivesTheAnalyticAlphaAndTransmittedBackground) {
  const CpuVolume box = constantBox({12, 8, 6}, 0.1f, 1.0f);
  scene::Smoke smoke;
  smoke.extinction = 2.5f;
  smoke.albedo = 0.0f;
  reference::TraceSettings s = settings(16, 8);
  s.background = {0.2f, 0.5f, 1.0f};
  const uint32_t n = 1024;
  const io::Image image = traceImage(box, smoke, s, n);
  const render::Camera camera = obliqueCamera();
  const render::ImagePlane plane = squareBillboard(camera, box.box());
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const auto [t0, t1] =
          rayBox(camera.position, cameraRay(camera, plane, {x + 0.5, y + 0.5}, 16, 16), box.box());
      const double T = std::exp(-smoke.extinction * std::max(0.0, t1 - t0));
      const double tolerance = 5 * std::sqrt(T * (1 - T) / n) + 1e-6;
      EXPECT_NEAR(image.at(x, y, 3), 1 - T, tolerance) << x << "," << y;
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(image.at(x, y, c), s.background[c] * T, s.background[c] * tolerance);
    }
}

// The furnace test: a non-absorbing (albedo 1) slab inside a uniform white environment, seen against a
// white background. Every path ends by leaving the slab with weight 1, so every pixel is exactly 1 with
// all scattering orders, whatever the slab's shape and phase function; cutting the orders loses energy.
TEST_F(PathTracerTest, WhiteSlabInAWhiteFurnaceConservesEnergy) {
  const CpuVolume slab = constantBox({16, 16, 4}, 1.0f / 16, 1.0f);
  scene::Smoke smoke;
  smoke.extinction = 8.0f;  // optical thickness 2 across the slab
  smoke.albedo = 1.0f;
  smoke.phaseG = 0.5f;
  reference::TraceSettings s = settings(16, 100000);
  s.jitter = true;
  s.background = glm::vec3(1.0f);
  s.environment[0] = glm::vec3(1.0f);
  const io::Image all = traceImage(slab, smoke, s, 64);
  double alphaSum = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(all.at(x, y, c), 1.0f, 1e-5) << x << "," << y;
      alphaSum += all.at(x, y, 3);
    }
  EXPECT_GT(alphaSum / 256, 0.3) << "the slab must cover the image";

  s.maxOrders = 1;
  const io::Image single = traceImage(slab, smoke, s, 64);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      if (all.at(x, y, 3) > 0.5f) {
        EXPECT_LT(single.at(x, y, 0), 0.95f) << x << "," << y;
      }
    }
}

// With one scattering order and pixel centres, the path tracer estimates what the baker computes. Against a
// finely discretised bake, the RMS error must fall as 1/√spp (log-log slope −0.5) over 16…1024 spp; against
// the default bake it must stay within the Monte Carlo error plus the baker's discretisation error (default
// vs fine bake).
TEST_F(PathTracerTest, SingleScatteringConvergesToTheBakerAsOneOverSqrtSpp) {
  const CpuVolume volume = puffs(16);
  const render::DeviceVolume device = upload(volume);
  const scene::Smoke smoke = puffOptics();
  const render::Camera camera = obliqueCamera();
  const render::ImagePlane plane = squareBillboard(camera, volume.box());
  reference::LightmapBaker baker(context(), pipelineCache());
  reference::BakeSettings coarse;
  coarse.width = coarse.height = 32;
  const io::Image baked = baker.bake(device.view(), smoke, camera, plane, coarse);
  reference::BakeSettings fineSettings = coarse;
  fineSettings.lightSpacingCells = 0.25f;
  fineSettings.stepCells = 0.125f;
  const io::Image fine = baker.bake(device.view(), smoke, camera, plane, fineSettings);
  // Not the emissive channel: with one order the tracer's holds the emission scattered once too, the baker's
  // only the direct emission (ScatteredLightmaps adds the scattered part).
  std::vector<int> channels(render::kSixWayChannels - 1);
  std::iota(channels.begin(), channels.end(), 0);
  const double discretisation = rms(baked, fine, channels);

  tracer_.beginSixWay(device.view(), smoke, camera, plane, settings(32, 1));
  std::vector<double> logSpp, logError;
  uint32_t done = 0;
  for (uint32_t spp : {16u, 64u, 256u, 1024u}) {
    tracer_.accumulate(spp - done);
    done = spp;
    logSpp.push_back(std::log(double(spp)));
    logError.push_back(std::log(rms(tracer_.image(), fine, channels)));
  }
  const double meanX = std::accumulate(logSpp.begin(), logSpp.end(), 0.0) / 4;
  const double meanY = std::accumulate(logError.begin(), logError.end(), 0.0) / 4;
  double sxy = 0, sxx = 0;
  for (int i = 0; i < 4; ++i) {
    sxy += (logSpp[i] - meanX) * (logError[i] - meanY);
    sxx += (logSpp[i] - meanX) * (logSpp[i] - meanX);
  }
  const double slope = sxy / sxx;
  RecordProperty("slope", std::to_string(slope));
  for (int i = 0; i < 4; ++i)
    RecordProperty("rms_" + std::to_string(16 << (2 * i)), std::to_string(std::exp(logError[i])));
  RecordProperty("rms_vs_default_bake_1024", std::to_string(rms(tracer_.image(), baked, channels)));
  RecordProperty("baker_discretisation_rms", std::to_string(discretisation));
  EXPECT_NEAR(slope, -0.5, 0.08) << "errors: " << std::exp(logError[0]) << " " << std::exp(logError[1]) << " "
                                 << std::exp(logError[2]) << " " << std::exp(logError[3]);
  const double monteCarlo = std::exp(logError[3]);
  EXPECT_LT(monteCarlo, 1.3 * std::exp(logError[0]) / 8) << "the error at 1024 spp stays on the 1/√spp line";
  EXPECT_LT(rms(tracer_.image(), baked, channels), 1.2 * std::hypot(monteCarlo, discretisation));
}

// Single scattering of a coloured point light (inverse-square falloff, Henyey–Greenstein phase, ratio-tracked
// shadow rays) against the CPU oracle, within 3× the measured Monte Carlo error.
TEST_F(PathTracerTest, PointLightSingleScatteringMatchesTheCpuOracle) {
  const CpuVolume volume = puffs(12);
  scene::Smoke smoke = puffOptics();
  smoke.emission.intensity = 0.0f;  // the oracle has no emission
  const glm::vec3 position(1.4f, 1.1f, 0.3f);
  const scene::Light lamp{scene::PointLight{position}, {1.0f, 0.7f, 0.4f}, 5.0f};
  reference::TraceSettings s = settings(16, 1);
  const io::Image a = traceImage(volume, smoke, s, 512, {lamp});
  s.seed = 2;
  const TwoSeeds traced = meanOfTwoSeeds(a, traceImage(volume, smoke, s, 512, {lamp}), {0, 1, 2});
  const render::Camera camera = obliqueCamera();
  const io::Image cpu =
      pointLightSingleScattering(volume, smoke, camera, squareBillboard(camera, volume.box()), 16, 16,
                                 position, lamp.color * lamp.intensity, 0.25);
  EXPECT_GT(peak(cpu, 0), 0.05);
  EXPECT_LT(traced.noise, 0.03 * peak(cpu, 0)) << "enough samples for the comparison to mean something";
  RecordProperty("rms", std::to_string(rms(traced.mean, cpu, {0, 1, 2})));
  RecordProperty("noise", std::to_string(traced.noise));
  EXPECT_LT(rms(traced.mean, cpu, {0, 1, 2}), 3 * traced.noise);
}

// Single scattering of an environment whose radiance varies linearly with direction, a different axis per
// colour channel (R: x, G: y, B: z), against the CPU oracle's quadrature over 600 directions. The path tracer
// reaches the environment only through Henyey–Greenstein sampling, so this checks the sampled directions.
TEST_F(PathTracerTest, EnvironmentSingleScatteringMatchesTheCpuOracle) {
  const CpuVolume volume = puffs(10);
  scene::Smoke smoke = puffOptics();
  smoke.emission.intensity = 0.0f;
  smoke.phaseG = 0.5f;
  const std::array<glm::vec3, 4> environment = {glm::vec3(0.5f), glm::vec3(0.45f, 0.0f, 0.0f),
                                                glm::vec3(0.0f, 0.45f, 0.0f), glm::vec3(0.0f, 0.0f, 0.45f)};
  reference::TraceSettings s = settings(12, 1);
  s.environment = environment;
  const io::Image a = traceImage(volume, smoke, s, 1024);
  s.seed = 7;
  const TwoSeeds traced = meanOfTwoSeeds(a, traceImage(volume, smoke, s, 1024), {0, 1, 2});
  const render::Camera camera = obliqueCamera();
  const io::Image cpu = environmentSingleScattering(
      volume, smoke, camera, squareBillboard(camera, volume.box()), 12, 12, environment, 600, 0.5);
  EXPECT_GT(peak(cpu, 0), 0.05);
  EXPECT_LT(traced.noise, 0.03 * peak(cpu, 0));
  RecordProperty("rms", std::to_string(rms(traced.mean, cpu, {0, 1, 2})));
  RecordProperty("noise", std::to_string(traced.noise));
  for (int c = 0; c < 3; ++c)
    EXPECT_LT(rms(traced.mean, cpu, {c}), 3 * traced.noise + 2e-3 * peak(cpu, c)) << c;
}

// The six lightmaps under a uniform white environment: light of radiance 1 from every direction is the
// six-way lights (irradiance π each) integrated over the sphere, and the six-point rule with weights 4π/6
// gives  L_env ≈ (4π/6) · Σ_i lightmap_i / π = (2/3) · Σ_i lightmap_i.  The rule is exact for an isotropic
// phase function and a light transmittance of degree ≤ 3 in the direction; its error for this thin smoke is
// measured with the CPU oracle, and the path tracer (environment, one order) must match the baker's sum
// within that error plus 3× the Monte Carlo error.
TEST_F(PathTracerTest, SixLightmapsSumToTheUniformEnvironment) {
  const CpuVolume volume = puffs(10);
  scene::Smoke smoke = puffOptics();
  smoke.emission.intensity = 0.0f;
  smoke.phaseG = 0.0f;
  smoke.extinction = 1.5f;
  const render::Camera camera = obliqueCamera();
  const render::ImagePlane plane = squareBillboard(camera, volume.box());
  auto sumOfSix = [](const io::Image& lightmaps) {
    io::Image sum(lightmaps.width, lightmaps.height, {"Y"});
    for (int y = 0; y < sum.height; ++y)
      for (int x = 0; x < sum.width; ++x)
        for (int c = 0; c < render::kSixWayLights; ++c)
          sum.at(x, y, 0) += lightmaps.at(x, y, c) * 2.0f / 3.0f;
    return sum;
  };
  const std::array<glm::vec3, 4> white = {glm::vec3(1.0f), glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
  const double rule = rms(environmentSingleScattering(volume, smoke, camera, plane, 12, 12, white, 600, 0.5),
                          sumOfSix(bakeSixWay(volume, smoke, camera, plane, 12, 12, 0.5)), {0});

  const render::DeviceVolume device = upload(volume);
  reference::LightmapBaker baker(context(), pipelineCache());
  reference::BakeSettings bake;
  bake.width = bake.height = 12;
  const io::Image expected = sumOfSix(baker.bake(device.view(), smoke, camera, plane, bake));
  reference::TraceSettings s = settings(12, 1);
  s.environment = white;
  const io::Image a = traceImage(volume, smoke, s, 1024);
  s.seed = 3;
  const TwoSeeds traced = meanOfTwoSeeds(a, traceImage(volume, smoke, s, 1024), {0});
  EXPECT_GT(peak(expected, 0), 0.1);
  EXPECT_LT(rule, 0.01 * peak(expected, 0)) << "the six-point rule is nearly exact for this smoke";
  RecordProperty("six_point_rule_rms", std::to_string(rule));
  RecordProperty("peak", std::to_string(peak(expected, 0)));
  RecordProperty("path_tracer_vs_sum_rms", std::to_string(rms(traced.mean, expected, {0})));
  RecordProperty("noise", std::to_string(traced.noise));
  EXPECT_LT(rms(traced.mean, expected, {0}), rule + 3 * traced.noise);
}

// Delta and ratio tracking across empty bricks and brick faces: on sparse smoke, the path tracer's alpha and
// single scattering match the CPU oracle (no bricks) within 3× the measured Monte Carlo error plus 1% of the
// peak (the oracle's own quadrature error).
TEST_F(PathTracerTest, SparseSmokeAcrossEmptyBricksMatchesTheCpuOracle) {
  const CpuVolume volume = sparseCones(24);
  const render::DeviceVolume device = upload(volume);
  scene::Smoke smoke = puffOptics();
  smoke.emission.intensity = 0.0f;
  const render::Camera camera = obliqueCamera();
  const render::ImagePlane plane = squareBillboard(camera, volume.box());
  const io::Image cpu = bakeSixWay(volume, smoke, camera, plane, 24, 24, 0.5);
  auto trace = [&](uint32_t seed) {
    reference::TraceSettings s = settings(24, 1);
    s.seed = seed;
    tracer_.beginSixWay(device.view(), smoke, camera, plane, s);
    tracer_.accumulate(512);
    return tracer_.image();
  };
  const std::vector<int> channels = {0, 1, 2, 3, 4, 5, render::Alpha};
  const TwoSeeds traced = meanOfTwoSeeds(trace(1), trace(2), channels);
  EXPECT_GT(peak(cpu, render::Alpha), 0.2);
  EXPECT_LT(rms(traced.mean, cpu, channels), 3 * traced.noise + 0.01 * peak(cpu, render::Back));
}

// A layer one cell thick next to a face between majorant bricks: the trilinear density spills half a cell
// into the neighbouring brick, whose majorant must cover it, or ratio tracking loses an eighth of the layer's
// optical depth (here 1). The mean alpha over the image must match the CPU oracle within 5 standard errors
// (pixels are independent; the per-pixel error is measured from two seeds).
TEST_F(PathTracerTest, LayerOnABrickFaceKeepsItsWholeOpticalDepth) {
  for (int layer : {7, 8}) {  // the last cell of brick 0, the first of brick 1
    const CpuVolume volume = makeVolume({16, 16, 16}, glm::vec3(0.0f), 1.0f / 16,
                                        [layer](dvec3 p) { return int(p.x * 16) == layer ? 1.0f : 0.0f; });
    const render::DeviceVolume device = upload(volume);
    scene::Smoke smoke;
    smoke.extinction = 16.0f;  // optical depth 1 straight through the layer
    smoke.albedo = 0.0f;
    const render::Camera camera =
        render::Camera::lookAt({3.0f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.5f}, {0, 1, 0}, 30.0f);
    const render::ImagePlane plane = squareBillboard(camera, volume.box());
    const io::Image cpu = bakeSixWay(volume, smoke, camera, plane, 16, 16, 0.05);
    auto trace = [&](uint32_t seed) {
      reference::TraceSettings s = settings(16, 1);
      s.seed = seed;
      tracer_.beginSixWay(device.view(), smoke, camera, plane, s);
      tracer_.accumulate(256);
      return tracer_.image();
    };
    const TwoSeeds traced = meanOfTwoSeeds(trace(1), trace(2), {render::Alpha});
    double traceMean = 0, cpuMean = 0;
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) {
        traceMean += traced.mean.at(x, y, render::Alpha) / 256.0;
        cpuMean += cpu.at(x, y, render::Alpha) / 256.0;
      }
    EXPECT_GT(cpuMean, 0.3) << layer;
    EXPECT_NEAR(traceMean, cpuMean, 5 * traced.noise / 16 + 1e-4) << "layer at cell " << layer;
  }
}

// A fixed seed gives the same image, however the samples are split into passes (up to the order of float
// additions); another seed gives another image.
TEST_F(PathTracerTest, FixedSeedReproducesTheImage) {
  const CpuVolume volume = puffs(10);
  reference::TraceSettings s = settings(12, 4);
  s.jitter = true;
  const scene::Light sun{scene::DirectionalLight{glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f))}};
  const io::Image first = traceImage(volume, puffOptics(), s, 32, {sun});
  const io::Image again = traceImage(volume, puffOptics(), s, 32, {sun});
  EXPECT_EQ(first.pixels, again.pixels);
  s.samplesPerPass = 4;
  const io::Image split = traceImage(volume, puffOptics(), s, 32, {sun});
  for (size_t i = 0; i < first.pixels.size(); ++i) ASSERT_NEAR(split.pixels[i], first.pixels[i], 1e-5f);
  s.seed = 99;
  EXPECT_GT(rms(traceImage(volume, puffOptics(), s, 32, {sun}), first, {0, 1, 2, 3}), 1e-3);
}

// With the same random numbers, more scattering orders only add light: the six-way lightmaps with multiple
// scattering are at least the single-scattering ones in every pixel, and brighter overall.
TEST_F(PathTracerTest, MultipleScatteringOnlyAddsLight) {
  const CpuVolume volume = puffs(12);
  const render::DeviceVolume device = upload(volume);
  const render::Camera camera = obliqueCamera();
  const render::ImagePlane plane = squareBillboard(camera, volume.box());
  auto lightmaps = [&](int orders) {
    tracer_.beginSixWay(device.view(), puffOptics(), camera, plane, settings(12, orders));
    tracer_.accumulate(64);
    return tracer_.image();
  };
  const io::Image single = lightmaps(1), multiple = lightmaps(64);
  double gain = 0;
  for (size_t i = 0; i < single.pixels.size(); ++i) {
    ASSERT_GE(multiple.pixels[i], single.pixels[i] * (1 - 1e-5f) - 1e-7f) << i;
    gain += multiple.pixels[i] - single.pixels[i];
  }
  EXPECT_GT(gain, 0.05 * std::accumulate(single.pixels.begin(), single.pixels.end(), 0.0));
}

}  // namespace
}  // namespace sixway::test
