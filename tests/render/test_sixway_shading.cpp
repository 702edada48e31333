// The six-way billboard shading (src/render/sixway_shading.h) against the CPU oracle (cpu_shading.h) on
// random lightmaps, lights, ambient and controls, and against closed forms: uniform lightmaps shade alike for
// every light direction, a uniform environment, shadows that remove exactly their light's share with the
// stated PCF ramp, obstacles that hide exactly the smoke behind them, the billboard's footprint, the default
// emissive gradient.
#include <gtest/gtest.h>

#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <iomanip>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

#include "cpu_shading.h"
#include "gpu/image.h"
#include "gpu/sequence.h"
#include "render/billboard.h"
#include "render/projection.h"
#include "render/sixway_shading.h"
#include "render/volume.h"
#include "support/gpu_fixture.h"
#include "support/input_error.h"

namespace sixway::test {
namespace {

using render::ShadingLight;
constexpr float kPi = std::numbers::pi_v<float>;
constexpr int kWidth = 48, kHeight = 40;

float uniform(std::mt19937& rng, float lo, float hi) {
  return std::uniform_real_distribution<float>(lo, hi)(rng);
}

glm::vec3 randomDirection(std::mt19937& rng) {
  glm::vec3 d;
  do d = {uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
  while (glm::length(d) < 0.2f || glm::length(d) > 1.0f);
  return glm::normalize(d);
}

// Half-precision storage: the values the GPU sees.
void roundToHalf(io::Image& image) {
  for (float& v : image.pixels) v = float(Imath::half(v));
}

std::string scientific(double value) {
  std::ostringstream out;
  out << std::scientific << std::setprecision(2) << value;
  return out.str();
}

// The largest |actual − expected| / (1 + |expected|) and where.
struct Mismatch {
  double worst = 0.0;
  int x = 0, y = 0, c = 0;
  double actual = 0.0, expected = 0.0;
};
Mismatch mismatch(const io::Image& actual, const io::Image& expected) {
  Mismatch m;
  for (int y = 0; y < expected.height; ++y)
    for (int x = 0; x < expected.width; ++x)
      for (int c = 0; c < 4; ++c) {
        const double e = expected.at(x, y, c), a = actual.at(x, y, c);
        const double err = std::abs(a - e) / (1.0 + std::abs(e));
        if (!(err <= m.worst)) m = {err, x, y, c, a, e};
      }
  return m;
}
std::ostream& operator<<(std::ostream& os, const Mismatch& m) {
  return os << "worst relative error " << m.worst << " at (" << m.x << ", " << m.y << ") channel " << m.c
            << ": " << m.actual << " vs " << m.expected;
}

class SixWayShadingTest : public GpuTest {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    camera = render::Camera::lookAt({0.6f, 0.5f, 3.2f}, {0.0f, 0.1f, 0.0f}, {0.0f, 1.0f, 0.0f}, 40.0f);
    in.camera = camera;
    in.frame = render::fullFrame(camera, kWidth, kHeight);
    in.billboard = in.frame;  // lightmap texels on pixel centres: the oracle's bilinear lookup is exact
    in.shellRange = render::boxDepthRange(camera, box);
    in.sceneRange = {0.3f, 12.0f};
  }

  // Random premultiplied lightmaps of the target's size: alpha in [0, 1] (an eighth exactly 0), light
  // channels alpha · [0, 1.3], emissive alpha · [0, 2].
  void randomLightmaps(std::mt19937& rng, bool half) {
    lightmapA = io::Image(kWidth, kHeight, {"R", "G", "B", "A"});
    lightmapB = io::Image(kWidth, kHeight, {"R", "G", "B", "A"});
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const float alpha = uniform(rng, 0, 1) < 0.125f ? 0.0f : uniform(rng, 0, 1);
        for (int c = 0; c < 3; ++c) {
          lightmapA.at(x, y, c) = alpha * uniform(rng, 0, 1.3f);
          lightmapB.at(x, y, c) = alpha * uniform(rng, 0, 1.3f);
        }
        lightmapA.at(x, y, 3) = alpha;
        lightmapB.at(x, y, 3) = alpha * uniform(rng, 0, 2);
      }
    if (half) {
      roundToHalf(lightmapA);
      roundToHalf(lightmapB);
    }
    lightmapFormat = half ? VK_FORMAT_R16G16B16A16_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT;
  }

  // A guide whose shell depth (B) is random in [0, 0.98] where `hasShell` says so, else 1 (no shell).
  void randomGuide(std::mt19937& rng, float shellFraction) {
    guide = io::Image(kWidth, kHeight, {"R", "G", "B", "A"});
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        guide.at(x, y, 2) = uniform(rng, 0, 1) < shellFraction ? uniform(rng, 0, 0.98f) : 1.0f;
  }

  void randomBackground(std::mt19937& rng) {
    background = io::Image(kWidth, kHeight, {"R", "G", "B", "A"});
    for (float& v : background.pixels) v = uniform(rng, 0.05f, 0.8f);
  }

  // 3–5 lights: directional from random directions and point lights 2–3.5 m from the volume's centre.
  std::vector<ShadingLight> randomLights(std::mt19937& rng) {
    std::vector<ShadingLight> lights(3 + rng() % 3);
    for (size_t i = 0; i < lights.size(); ++i) {
      ShadingLight& l = lights[i];
      const glm::vec3 color(uniform(rng, 0.2f, 1), uniform(rng, 0.2f, 1), uniform(rng, 0.2f, 1));
      if (i % 2 == 0) {
        l.type = ShadingLight::Type::Directional;
        l.vector = randomDirection(rng);
        l.radiance = color * uniform(rng, 0.5f, 4.0f);
      } else {
        l.type = ShadingLight::Type::Point;
        l.vector = randomDirection(rng) * uniform(rng, 2.0f, 3.5f);
        l.radiance = color * uniform(rng, 3.0f, 20.0f);
      }
    }
    return lights;
  }

  static scene::Ambient randomSh(std::mt19937& rng) {
    scene::AmbientSh sh;
    sh.coefficients[0] = {uniform(rng, 0.05f, 0.3f), uniform(rng, 0.05f, 0.3f), uniform(rng, 0.05f, 0.3f)};
    for (int i = 1; i < 4; ++i)
      for (int c = 0; c < 3; ++c) sh.coefficients[i][c] = uniform(rng, -0.5f, 0.5f) * sh.coefficients[0][c];
    return sh;
  }

  gpu::Image rgbaImage(const io::Image& image, VkFormat format, const char* name) {
    gpu::Image gpuImage(context(), {uint32_t(image.width), uint32_t(image.height), 1, format,
                                    VK_IMAGE_USAGE_SAMPLED_BIT, name});
    if (format == VK_FORMAT_R16G16B16A16_SFLOAT) {
      std::vector<Imath::half> halves(image.pixels.begin(), image.pixels.end());
      gpuImage.upload(std::as_bytes(std::span(halves)));
    } else {
      gpuImage.upload(std::as_bytes(std::span(image.pixels)));
    }
    return gpuImage;
  }

  gpu::Image depthImage(const io::Image& image, const char* name) {
    gpu::Image gpuImage(context(), {uint32_t(image.width), uint32_t(image.height), 1, VK_FORMAT_D32_SFLOAT,
                                    VK_IMAGE_USAGE_SAMPLED_BIT, name});
    gpuImage.upload(std::as_bytes(std::span(image.pixels)));
    return gpuImage;
  }

  // Renders the inputs `in` (lights, ambient, controls) over the background, recording once and replaying
  // for each of `frames` (each sets `in` before its submission).
  struct Frame {
    std::vector<ShadingLight> lights;
    std::optional<scene::Ambient> ambient;
    render::ShadingControls controls;
  };
  std::vector<io::Image> render(const std::vector<Frame>& frames, bool withGuide, bool withObstacles,
                                bool withAtlas) {
    const gpu::Image a = rgbaImage(lightmapA, lightmapFormat, "lightmap A");
    const gpu::Image b = rgbaImage(lightmapB, lightmapFormat, "lightmap B");
    std::optional<gpu::Image> g, depth, shadowAtlas;
    if (withGuide) g.emplace(rgbaImage(guide, VK_FORMAT_R32G32B32A32_SFLOAT, "guide"));
    if (withObstacles) depth.emplace(depthImage(obstacleDepth, "obstacle depth"));
    if (withAtlas) shadowAtlas.emplace(depthImage(atlas, "shadow atlas"));
    std::optional<gpu::Image> levels;
    if (in.opacityDepths)
      levels.emplace(rgbaImage(opacityDepths, VK_FORMAT_R32G32B32A32_SFLOAT, "opacity depths"));
    gpu::Image target(context(), {kWidth, kHeight, 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                                  VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "target"});
    render::SixWayShading shading(context(), pipelineCache(), VK_FORMAT_R32G32B32A32_SFLOAT, 8);
    render::ShadowAtlas shadows;
    if (withAtlas) shadows = {&*shadowAtlas, uint32_t(atlas.width), float(in.pcfRadius), float(in.depthBias)};
    gpu::Sequence sequence(context());
    shading.record(sequence, a, b, g ? &*g : nullptr, levels ? &*levels : nullptr, depth ? &*depth : nullptr,
                   shadows, target);
    sequence.finish();

    std::vector<io::Image> images;
    for (const Frame& f : frames) {
      shading.update(camera, in.frame, in.billboard, in.shellRange, depthMapping(in.sceneRange), f.lights,
                     f.ambient, f.controls);
      target.upload(std::as_bytes(std::span(background.pixels)));
      sequence.submit();
      io::Image image(kWidth, kHeight, {"R", "G", "B", "A"});
      target.download(std::as_writable_bytes(std::span(image.pixels)));
      images.push_back(std::move(image));
    }
    return images;
  }

  io::Image expected(const Frame& f, bool withGuide, bool withObstacles, bool withAtlas) {
    CpuShadingInputs c = in;
    c.lights = f.lights;
    c.ambient = f.ambient;
    c.controls = f.controls;
    c.lightmapA = &lightmapA;
    c.lightmapB = &lightmapB;
    c.guide = withGuide ? &guide : nullptr;
    c.obstacleDepth = withObstacles ? &obstacleDepth : nullptr;
    c.shadowAtlas = withAtlas ? &atlas : nullptr;
    c.tileSize = atlas.width;
    return cpuSixWayShading(c, background);
  }

  const render::Box box{glm::vec3(-1.0f), glm::vec3(1.0f)};
  render::Camera camera;
  CpuShadingInputs in;
  io::Image lightmapA, lightmapB, guide, background, obstacleDepth, atlas, opacityDepths;  // in.opacityDepths
  VkFormat lightmapFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
};

// Float arithmetic on the GPU against double precision: the largest terms are ~3 and pass through pow() with
// exponents up to ~3 (absorption), so a few float ulps of 3 become ~1e-6 relative; 2e-5 leaves room and is
// still 100x below the smallest effect of a wrong channel, sign or frame axis (> 1e-3 on these random
// inputs).
constexpr double kTolerance = 2e-5;

struct Variant {
  const char* name;
  bool absorption, lightmapRemap, alphaRemap, halfLightmaps;
};

void PrintTo(const Variant& v, std::ostream* os) {
  *os << v.name;
}

class SixWayShadingVariants : public SixWayShadingTest, public ::testing::WithParamInterface<Variant> {};

TEST_P(SixWayShadingVariants, MatchesTheCpuEvaluationOnRandomInputs) {
  const Variant v = GetParam();
  std::mt19937 rng(1234 + v.absorption + 2 * v.lightmapRemap + 4 * v.alphaRemap + 8 * v.halfLightmaps);
  randomLightmaps(rng, v.halfLightmaps);
  randomGuide(rng, 0.5f);
  randomBackground(rng);

  // Two frames replayed from one recording, with different lights, ambient and controls.
  std::vector<Frame> frames(2);
  for (Frame& f : frames) {
    f.lights = randomLights(rng);
    f.ambient = randomSh(rng);
    f.controls.color = {uniform(rng, 0.1f, 1), uniform(rng, 0.1f, 1), uniform(rng, 0.1f, 1)};
    f.controls.absorption = v.absorption;
    f.controls.absorptionStrength = uniform(rng, 0, 1);
    if (v.lightmapRemap) f.controls.lightmapRemap = render::RemapRange{0.1f, 0.9f, 0.05f, 1.4f};
    if (v.alphaRemap) f.controls.alphaRemap = render::RemapRange{0.05f, 0.8f, 0.0f, 1.0f};
    f.controls.emissiveGradient = {
        {0.2f, {0.4f, 0.05f, 0.0f}}, {0.7f, {1.0f, 0.5f, 0.1f}}, {1.5f, {1, 1, 0.9f}}};
    f.controls.emissiveMultiplier = uniform(rng, 0.5f, 2.0f);
  }
  frames[1].controls.emissiveStraightScale = uniform(rng, 0.05f, 0.5f);  // sixway's own lightmaps
  const std::vector<io::Image> images = render(frames, true, false, false);
  for (size_t i = 0; i < frames.size(); ++i) {
    const Mismatch m = mismatch(images[i], expected(frames[i], true, false, false));
    EXPECT_LT(m.worst, kTolerance) << "frame " << i << ": " << m;
    RecordProperty("frame" + std::to_string(i) + "_worst_relative_error", scientific(m.worst));
  }
  // The frames differ: the second is not a stale replay of the first.
  EXPECT_GT(mismatch(images[0], images[1]).worst, 1e-2);
}

INSTANTIATE_TEST_SUITE_P(Controls, SixWayShadingVariants,
                         ::testing::Values(Variant{"Tint", false, false, false, false},
                                           Variant{"Absorption", true, false, false, false},
                                           Variant{"TintRemapped", false, true, true, false},
                                           Variant{"AbsorptionRemappedHalf", true, true, false, true}),
                         [](const auto& info) { return std::string(info.param.name); });

// With all six light channels equal, t = Σ d_i² w = w for every unit d: one directional light gives the same
// image from any direction, E/π · colour · w (+ the background behind). With absorption too.
TEST_F(SixWayShadingTest, UniformLightmapsShadeAlikeForEveryLightDirection) {
  std::mt19937 rng(7);
  randomLightmaps(rng, false);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      for (int c = 0; c < 3; ++c) lightmapA.at(x, y, c) = lightmapB.at(x, y, c) = lightmapA.at(x, y, 0);
  randomBackground(rng);
  const glm::vec3 radiance(2.0f, 1.5f, 0.7f);
  std::vector<glm::vec3> directions = {{1, 0, 0}, {0, -1, 0}, {0, 0, 1}, glm::normalize(glm::vec3(1, 1, 1))};
  for (int i = 0; i < 4; ++i) directions.push_back(randomDirection(rng));
  for (bool absorption : {false, true}) {
    std::vector<Frame> frames;
    for (const glm::vec3& d : directions) {
      Frame f;
      f.lights = {ShadingLight{ShadingLight::Type::Directional, d, radiance}};
      f.controls.absorption = absorption;
      f.controls.color = {0.9f, 0.6f, 0.3f};
      f.controls.emissiveGradient = {{1.0f, glm::vec3(0.0f)}};  // no emission: only the light
      frames.push_back(f);
    }
    const std::vector<io::Image> images = render(frames, false, false, false);
    double spread = 0.0;
    for (const io::Image& image : images) spread = std::max(spread, mismatch(image, images[0]).worst);
    EXPECT_LT(spread, 1e-6) << "absorption " << absorption;
    RecordProperty(absorption ? "spread_absorption" : "spread_tint", scientific(spread));
    if (!absorption) {  // the closed form: E/π · tint · w + (1 − alpha) · background
      double worst = 0.0;
      for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
          for (int c = 0; c < 3; ++c) {
            const double w = lightmapA.at(x, y, 0), alpha = lightmapA.at(x, y, 3);
            const double e =
                radiance[c] / kPi * frames[0].controls.color[c] * w + (1 - alpha) * background.at(x, y, c);
            worst = std::max(worst, std::abs(images[0].at(x, y, c) - e));
          }
      EXPECT_LT(worst, 1e-5);
      RecordProperty("closed_form_error", scientific(worst));
    }
  }
}

// A uniform environment of radiance c lights uniform lightmaps w (light response w under irradiance π from
// any direction) by ∫ c · w / π dω = 4 · c · w: Unity's (4π/6)·Σ on radiance/π, i.e. (2/3)·Σ on radiance.
TEST_F(SixWayShadingTest, UniformEnvironmentGivesFourTimesRadianceTimesUniformLightmaps) {
  std::mt19937 rng(8);
  randomLightmaps(rng, false);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      for (int c = 0; c < 3; ++c) lightmapA.at(x, y, c) = lightmapB.at(x, y, c) = lightmapA.at(x, y, 1);
  background = io::Image(kWidth, kHeight, {"R", "G", "B", "A"});
  const glm::vec3 c(0.3f, 0.2f, 0.1f);
  Frame constant, sh;
  constant.ambient = scene::AmbientColor{c};
  scene::AmbientSh coefficients;
  coefficients.coefficients[0] = c;
  sh.ambient = coefficients;
  for (Frame* f : {&constant, &sh}) f->controls.emissiveGradient = {{1.0f, glm::vec3(0.0f)}};
  const std::vector<io::Image> images = render({constant, sh}, false, false, false);
  double worst = 0.0;
  for (const io::Image& image : images)
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        for (int k = 0; k < 3; ++k)
          worst = std::max(worst, std::abs(image.at(x, y, k) - 4.0 * c[k] * lightmapA.at(x, y, 1)));
  EXPECT_LT(worst, 1e-6);
  RecordProperty("error", scientific(worst));
}

// Shadows from a synthetic atlas of two 32² tiles: tile 0 empty (depth 1), tile 1 a half-plane occluder at
// depth 0.1 over texel columns 0..12. Light 0 (tile 0) stays lit; light 1 (tile 1, orthographic, the shell
// points at light depths 0.12..0.98) loses exactly its share, times 1 − v with the PCF ramp v = clamp((x − 13
// + R)/(2R)) in texel units x across the edge (R = 1.5), and points outside its frustum are lit.
TEST_F(SixWayShadingTest, ShadowsRemoveExactlyTheirLightsShareWithTheStatedPcfRamp) {
  std::mt19937 rng(9);
  randomLightmaps(rng, false);
  randomGuide(rng, 1.0f);
  in.guide = &guide;
  randomBackground(rng);
  constexpr int kTile = 32, kEdge = 13;
  atlas = io::Image(kTile, 2 * kTile, {"depth"});
  for (int y = 0; y < 2 * kTile; ++y)
    for (int x = 0; x < kTile; ++x) atlas.at(x, y, 0) = (y >= kTile && x < kEdge) ? 0.1f : 1.0f;
  in.pcfRadius = 1.5;
  in.depthBias = 0.002;

  const glm::vec3 toLight = glm::normalize(glm::vec3(-1.0f, 1.0f, 0.5f));
  const glm::mat4 lightView = glm::lookAtRH(toLight * 5.0f, glm::vec3(0.0f), glm::vec3(0, 1, 0));
  const glm::mat4 lightMatrix = glm::orthoRH_ZO(-1.1f, 1.1f, -1.3f, 1.3f, 2.0f, 8.0f) * lightView;
  ShadingLight lit{ShadingLight::Type::Directional,
                   glm::normalize(glm::vec3(0.3f, -0.2f, -1.0f)),
                   {1.0f, 1.5f, 2.0f},
                   0,
                   lightMatrix};
  ShadingLight shadowed{ShadingLight::Type::Directional, toLight, {3.0f, 2.5f, 2.0f}, 1, lightMatrix};
  Frame both, withoutShadowed;
  both.lights = {lit, shadowed};
  withoutShadowed.lights = {lit};
  both.ambient = withoutShadowed.ambient = randomSh(rng);

  const io::Image unshadowed = render({both}, true, false, false)[0];
  const std::vector<io::Image> withAtlas = render({both, withoutShadowed}, true, false, true);
  const Mismatch m = mismatch(withAtlas[0], expected(both, true, false, true));
  EXPECT_LT(m.worst, kTolerance) << m;
  RecordProperty("oracle_error", scientific(m.worst));

  // The shadowed image = the image without light 1 + v · (light 1's share), v from the closed form.
  int outside = 0, dark = 0, ramp = 0, full = 0;
  double worst = 0.0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const glm::dvec3 p = cpuShadedPoint(in, kWidth, kHeight, x, y);
      const glm::vec4 clip = lightMatrix * glm::vec4(glm::vec3(p), 1.0f);
      double v = 1.0;
      if (std::abs(clip.x) > 1.0f || std::abs(clip.y) > 1.0f) {
        ++outside;
      } else {
        ASSERT_GT(clip.z, 0.12f);  // behind the occluder, inside the depth range
        ASSERT_LT(clip.z, 0.98f);
        const double texel = (0.5 + 0.5 * clip.x) * kTile;
        v = std::clamp((texel - kEdge + in.pcfRadius) / (2 * in.pcfRadius), 0.0, 1.0);
        ++(v == 0.0 ? dark : v == 1.0 ? full : ramp);
      }
      for (int c = 0; c < 3; ++c) {
        const double share = unshadowed.at(x, y, c) - withAtlas[1].at(x, y, c);
        worst = std::max(worst, std::abs(withAtlas[0].at(x, y, c) - (withAtlas[1].at(x, y, c) + v * share)));
      }
    }
  EXPECT_LT(worst, 1e-5);
  RecordProperty("share_error", scientific(worst));
  RecordProperty("pixels", std::to_string(outside) + " outside, " + std::to_string(dark) + " dark, " +
                               std::to_string(ramp) + " ramp, " + std::to_string(full) + " lit");
  EXPECT_GT(outside, 20);
  EXPECT_GT(dark, 100);
  EXPECT_GT(ramp, 20);
  EXPECT_GT(full, 100);
}

// A synthetic obstacle depth buffer 0.05–0.5 m in front of or behind each pixel's shaded point (the shell, or
// the billboard's plane where there is none), or empty (1): the smoke shows exactly where the obstacle is
// behind it; elsewhere the target keeps its background.
TEST_F(SixWayShadingTest, ObstaclesHideExactlyTheSmokeBehindThem) {
  std::mt19937 rng(10);
  randomLightmaps(rng, false);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) lightmapA.at(x, y, 3) = std::max(lightmapA.at(x, y, 3), 0.1f);
  randomGuide(rng, 0.6f);
  randomBackground(rng);
  in.guide = &guide;
  obstacleDepth = io::Image(kWidth, kHeight, {"depth"});
  std::vector<bool> hidden(kWidth * kHeight);
  const double n = in.sceneRange.near, f = in.sceneRange.far;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const double smoke = glm::dot(cpuShadedPoint(in, kWidth, kHeight, x, y) - glm::dvec3(camera.position),
                                    glm::dvec3(camera.forward));
      const float kind = uniform(rng, 0, 1);
      const double z = smoke + (kind < 0.4f ? -1.0 : 1.0) * uniform(rng, 0.05f, 0.5f);
      obstacleDepth.at(x, y, 0) = kind < 0.8f ? float(f * (z - n) / (z * (f - n))) : 1.0f;
      hidden[y * kWidth + x] = kind < 0.4f;
    }
  Frame frame;
  frame.lights = randomLights(rng);
  frame.ambient = randomSh(rng);
  const io::Image image = render({frame}, true, true, false)[0];
  const Mismatch m = mismatch(image, expected(frame, true, true, false));
  EXPECT_LT(m.worst, kTolerance) << m;
  RecordProperty("oracle_error", scientific(m.worst));
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      double difference = 0.0;
      for (int c = 0; c < 4; ++c)
        difference = std::max(difference, double(std::abs(image.at(x, y, c) - background.at(x, y, c))));
      if (hidden[y * kWidth + x])
        EXPECT_EQ(difference, 0.0) << x << ", " << y;
      else
        EXPECT_GT(difference, 1e-3) << x << ", " << y;
    }
}

// The smoke as a volume against obstacles: random opacity depths (0–4 of the levels reached, in depth order,
// the guide's fine or coarse alpha the ray's total opacity), random obstacle depths inside the smoke's depth
// range (a fifth without obstacle) and two lights, one shadowed by a half-plane occluder: each pixel against
// the oracle (the share of opacity in front of the obstacle, bilinear; shadows averaged over three depths).
// Then closed forms on uniform opacity depths: an obstacle halfway between the 0.35 and 0.6 levels of a ray
// of total opacity 0.95 lets 0.475 / 0.95 of the smoke through, one in front of the ramp hides it all, one
// behind the ray's end hides nothing.
TEST_F(SixWayShadingTest, ObstaclesInsideTheSmokeShowTheShareOfItInFront) {
  std::mt19937 rng(11);
  randomLightmaps(rng, false);
  randomGuide(rng, 0.8f);
  randomBackground(rng);
  in.guide = &guide;
  in.opacityDepths = &opacityDepths;
  constexpr double kLevels[4] = {0.1, 0.35, 0.6, 0.85};
  opacityDepths = io::Image(kWidth, kHeight, {"R", "G", "B", "A"});
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const int reached = int(rng() % 5);
      std::array<float, 4> depths{uniform(rng, 0.02f, 0.95f), uniform(rng, 0.02f, 0.95f),
                                  uniform(rng, 0.02f, 0.95f), uniform(rng, 0.02f, 0.95f)};
      std::sort(depths.begin(), depths.end());
      for (int k = 0; k < 4; ++k) opacityDepths.at(x, y, k) = k < reached ? depths[k] : 1.0f;
      const float total = reached == 0 ? (uniform(rng, 0, 1) < 0.3f ? 0.0f : uniform(rng, 0.01f, 0.1f))
                                       : uniform(rng, float(kLevels[reached - 1]),
                                                 reached < 4 ? float(kLevels[reached]) : 1.0f);
      const bool fine = uniform(rng, 0, 1) < 0.5f;
      guide.at(x, y, 1) = fine ? uniform(rng, 0, 1) : total;
      guide.at(x, y, 3) = fine ? total : 0.0f;
    }
  obstacleDepth = io::Image(kWidth, kHeight, {"depth"});
  const double n = in.sceneRange.near, f = in.sceneRange.far;
  const auto depthBufferValue = [&](double z) { return float(f * (z - n) / (z * (f - n))); };
  for (float& d : obstacleDepth.pixels)
    d = uniform(rng, 0, 1) < 0.2f
            ? 1.0f
            : depthBufferValue(uniform(rng, in.shellRange.near - 0.1f, in.shellRange.far));
  constexpr int kTile = 32;
  atlas = io::Image(kTile, kTile, {"depth"});
  for (int y = 0; y < kTile; ++y)
    for (int x = 0; x < kTile; ++x) atlas.at(x, y, 0) = x < 15 ? 0.1f : 1.0f;
  const glm::vec3 toLight = glm::normalize(glm::vec3(-1.0f, 1.0f, 0.5f));
  const glm::mat4 lightMatrix = glm::orthoRH_ZO(-1.1f, 1.1f, -1.3f, 1.3f, 2.0f, 8.0f) *
                                glm::lookAtRH(toLight * 5.0f, glm::vec3(0.0f), glm::vec3(0, 1, 0));
  Frame frame;
  frame.lights = {ShadingLight{ShadingLight::Type::Directional, toLight, {3.0f, 2.5f, 2.0f}, 0, lightMatrix},
                  ShadingLight{ShadingLight::Type::Point, {0.5f, 2.0f, 1.5f}, {4.0f, 3.0f, 2.0f}, -1, {}}};
  frame.ambient = randomSh(rng);
  const io::Image image = render({frame}, true, true, true)[0];
  const Mismatch m = mismatch(image, expected(frame, true, true, true));
  EXPECT_LT(m.worst, kTolerance) << m;
  RecordProperty("oracle_error", scientific(m.worst));
  // The random case mixes hidden, partly and wholly visible smoke.
  int hidden = 0, partly = 0, whole = 0;
  const io::Image unobstructed = [&] {
    CpuShadingInputs c = in;
    c.obstacleDepth = nullptr;
    c.lights = frame.lights;
    c.ambient = frame.ambient;
    c.lightmapA = &lightmapA;
    c.lightmapB = &lightmapB;
    c.shadowAtlas = &atlas;
    c.tileSize = atlas.width;
    return cpuSixWayShading(c, background);
  }();
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (lightmapA.at(x, y, 3) < 0.05f) continue;
      const double drawn = image.at(x, y, 3) - background.at(x, y, 3),
                   full = unobstructed.at(x, y, 3) - background.at(x, y, 3);
      ++(std::abs(drawn) < 1e-6 ? hidden : std::abs(drawn - full) < 1e-6 ? whole : partly);
    }
  RecordProperty("pixels", std::to_string(hidden) + " hidden, " + std::to_string(partly) + " partly, " +
                               std::to_string(whole) + " wholly visible");
  EXPECT_GT(hidden, 50);
  EXPECT_GT(partly, 300);
  EXPECT_GT(whole, 50);

  // Closed forms: every texel's levels at view depths 3.0, 3.2, 3.4, 3.6 m (inside the box's range), total
  // 0.95.
  const double near = in.shellRange.near, far = in.shellRange.far;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      for (int k = 0; k < 4; ++k) opacityDepths.at(x, y, k) = float((3.0 + 0.2 * k - near) / (far - near));
      guide.at(x, y, 1) = 0.5f;
      guide.at(x, y, 3) = 0.95f;
    }
  // Ambient light only: no term depends on the shaded point, which the obstacle moves.
  frame.lights.clear();
  const io::Image unhidden = render({frame}, true, false, false)[0];
  for (const auto& [obstacle, share] :
       {std::pair{3.3, 0.475 / 0.95}, std::pair{2.5, 0.0}, std::pair{4.5, 1.0}}) {
    SCOPED_TRACE("obstacle at " + std::to_string(obstacle) + " m");
    std::fill(obstacleDepth.pixels.begin(), obstacleDepth.pixels.end(), depthBufferValue(obstacle));
    const io::Image composite = render({frame}, true, true, false)[0];
    double worst = 0.0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        // Unhidden: smoke + (1 − alpha) · background, alpha from the A channel; a share s of the smoke
        // gives s · smoke + (1 − s · alpha) · background.
        const double alpha = (unhidden.at(x, y, 3) - background.at(x, y, 3)) / (1.0 - background.at(x, y, 3));
        for (int c = 0; c < 4; ++c) {
          const double smoke = c < 3 ? unhidden.at(x, y, c) - (1.0 - alpha) * background.at(x, y, c) : alpha;
          const double expected = share * smoke + (1.0 - share * alpha) * background.at(x, y, c);
          worst = std::max(worst, std::abs(composite.at(x, y, c) - expected));
        }
      }
    RecordProperty("closed_form_error_" + std::to_string(int(obstacle * 10)), scientific(worst));
    EXPECT_LT(worst, 1e-5);
  }
}

// A billboard smaller than the frame, its edges between pixel centres, with coarse 8 x 6 lightmaps stretched
// over it: the smoke covers exactly the pixels whose centres lie inside it (the rest keep the background),
// and each pixel shows the lightmaps at its own point of the billboard (rows from the top) through the
// Catmull-Rom cubic. The texels are random (alpha 0.2–1, so the cubic's overshoot is clamped at 1 in places);
// the weights are computed in the shader from texel fetches, exact to float rounding, while a bilinear lookup
// or a half-texel shift errs by ≥ 2e-2.
TEST_F(SixWayShadingTest, BillboardShowsItsLightmapsOverExactlyItsRectangle) {
  std::mt19937 rng(11);
  const glm::vec2 pixel = (in.frame.max - in.frame.min) / glm::vec2(kWidth, kHeight);
  in.billboard = {in.frame.min + pixel * glm::vec2(7.3f, 5.6f),
                  in.frame.min + pixel * glm::vec2(31.8f, 29.2f)};
  lightmapA = io::Image(8, 6, {"R", "G", "B", "A"});
  lightmapB = io::Image(8, 6, {"R", "G", "B", "A"});
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 8; ++x) {
      const float alpha = uniform(rng, 0.2f, 1.0f);
      for (int c = 0; c < 3; ++c) {
        lightmapA.at(x, y, c) = alpha * uniform(rng, 0.0f, 1.3f);
        lightmapB.at(x, y, c) = alpha * uniform(rng, 0.0f, 1.3f);
      }
      lightmapA.at(x, y, 3) = alpha;
      lightmapB.at(x, y, 3) = alpha * uniform(rng, 0.0f, 0.5f);
    }
  randomBackground(rng);
  Frame frame;
  frame.lights = randomLights(rng);
  frame.ambient = randomSh(rng);
  const io::Image image = render({frame}, false, false, false)[0];
  const Mismatch m = mismatch(image, expected(frame, false, false, false));
  EXPECT_LT(m.worst, kTolerance) << m;
  RecordProperty("oracle_error", scientific(m.worst));
  int covered = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) covered += image.at(x, y, 3) != background.at(x, y, 3);
  EXPECT_EQ(covered, 25 * 23);  // pixel centres 7.5 .. 31.5 across, 6.5 .. 28.5 up from the bottom
}

// The default gradient from an emission ramp keeps the emissive channel's luminance (what the baker wrote)
// and shows each ramp key's own colour at that key's luminance.
TEST_F(SixWayShadingTest, DefaultEmissiveGradientKeepsTheBakedLuminance) {
  scene::Emission emission;
  emission.intensity = 2.0f;
  emission.ramp = {
      {0.0f, {0, 0, 0}}, {0.3f, {0.6f, 0.1f, 0.0f}}, {0.6f, {1.0f, 0.5f, 0.1f}}, {1.0f, {1, 0.95f, 0.9f}}};
  const std::vector<render::GradientKey> keys = render::emissiveGradientFromRamp(emission);
  ASSERT_EQ(keys.size(), 3u);  // the black key adds nothing: black at 0 is implied
  auto luminance = [](glm::vec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };

  lightmapA = io::Image(kWidth, kHeight, {"R", "G", "B", "A"});
  lightmapB = io::Image(kWidth, kHeight, {"R", "G", "B", "A"});
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      lightmapA.at(x, y, 3) = 1.0f;
      lightmapB.at(x, y, 3) = 3.0f * float(y * kWidth + x) / (kWidth * kHeight);  // 0 .. 3, past the last key
    }
  for (int i = 0; i < 3; ++i) lightmapB.at(i, 0, 3) = float(luminance(keys[i].color));
  background = io::Image(kWidth, kHeight, {"R", "G", "B", "A"});
  Frame frame;
  frame.controls.emissiveGradient = keys;
  const io::Image image = render({frame}, false, false, false)[0];
  double worst = 0.0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const glm::vec3 rgb(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2));
      worst = std::max(worst, std::abs(luminance(rgb) - lightmapB.at(x, y, 3)));
    }
  EXPECT_LT(worst, 1e-6);
  RecordProperty("luminance_error", scientific(worst));
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.at(i, 0, c), keys[i].color[c], 1e-5) << "key " << i;
}

// With the straight scale s, lightmaps of smoke at one temperature shade to the ramp's colour at that
// temperature times alpha · s, however thick the smoke: the hue no longer follows the emissive channel's
// brightness (Unity's gradient(e) would turn thin hot smoke into the coolest key's colour).
TEST_F(SixWayShadingTest, StraightEmissionShowsTheRampColourAtAnyThickness) {
  scene::Emission emission;
  emission.intensity = 4.0f;
  emission.ramp = {
      {0.3f, {0, 0, 0}}, {1.0f, {1.0f, 0.25f, 0.02f}}, {2.0f, {1.0f, 0.65f, 0.2f}}, {3.0f, {1, 0.95f, 0.8f}}};
  scene::Smoke smoke;
  smoke.extinction = 30.0f;
  smoke.emission = emission;
  const float s = *render::emissiveStraightScale(smoke);
  EXPECT_FLOAT_EQ(s, 4.0f / 30.0f);
  auto luminance = [](glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; };
  const glm::vec3 hot{1.0f, 0.8f, 0.5f};  // the ramp at temperature 2.5: halfway between its last two keys

  lightmapA = io::Image(kWidth, kHeight, {"R", "G", "B", "A"});
  lightmapB = io::Image(kWidth, kHeight, {"R", "G", "B", "A"});
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const float alpha = 0.02f + 0.98f * float(x) / float(kWidth - 1);  // thin to opaque
      lightmapA.at(x, y, 3) = alpha;
      lightmapB.at(x, y, 3) = alpha * s * luminance(hot);  // what the baker writes for one temperature
    }
  background = io::Image(kWidth, kHeight, {"R", "G", "B", "A"});
  Frame frame;
  frame.controls.emissiveGradient = render::emissiveGradientFromRamp(emission);
  frame.controls.emissiveStraightScale = s;
  const io::Image image = render({frame}, false, false, false)[0];
  double worst = 0.0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      for (int c = 0; c < 3; ++c) {
        const double expected = lightmapA.at(x, y, 3) * s * hot[c];
        worst = std::max(worst, std::abs(image.at(x, y, c) - expected) / (expected + 1e-6));
      }
  EXPECT_LT(worst, 1e-4);
  RecordProperty("relative_error", scientific(worst));
}

TEST_F(SixWayShadingTest, MoreLightsThanItTakesIsAnInputError) {
  render::SixWayShading shading(context(), pipelineCache(), VK_FORMAT_R32G32B32A32_SFLOAT, 4);
  const std::vector<ShadingLight> lights(5);
  const std::string message = inputErrorMessage([&] {
    shading.update(camera, in.frame, in.billboard, in.shellRange, depthMapping(in.sceneRange), lights,
                   std::nullopt, {});
  });
  EXPECT_NE(message.find("5 lights"), std::string::npos) << message;
  EXPECT_NE(message.find("at most 4"), std::string::npos) << message;
}

TEST(SixWayShadingLights, SceneLightsBecomeShadingLights) {
  scene::Light point;
  point.source = scene::PointLight{{1, 2, 3}};
  point.color = {1.0f, 0.5f, 0.25f};
  point.intensity = 8.0f;
  point.shadows = false;
  const ShadingLight p = render::shadingLight(point, 2);
  EXPECT_EQ(p.type, ShadingLight::Type::Point);
  EXPECT_EQ(p.vector, glm::vec3(1, 2, 3));
  EXPECT_EQ(p.radiance, glm::vec3(8.0f, 4.0f, 2.0f));
  EXPECT_EQ(p.shadowTile, -1);  // the light casts no shadows
  scene::Light sun;
  sun.source = scene::DirectionalLight{{0, 2, 0}};
  const ShadingLight s = render::shadingLight(sun, 1);
  EXPECT_EQ(s.type, ShadingLight::Type::Directional);
  EXPECT_EQ(s.vector, glm::vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(s.radiance.x, kPi);
  EXPECT_EQ(s.shadowTile, 1);
}

}  // namespace
}  // namespace sixway::test
