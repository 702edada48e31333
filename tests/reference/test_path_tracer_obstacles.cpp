// Obstacles in the path tracer (path_trace.comp with render::ObstacleBvh) against closed forms: an opaque
// sphere over a homogeneous slab lit from above casts a shadow that is a vertical cylinder of the sphere's
// radius, so the slab's single scattering along each camera ray is a one-dimensional integral with the
// shadowed chord left out; a sphere under the slab is lit through the whole slab, exp(−σ_t·H), and covers
// the pixels it fills (alpha 1) with its Lambertian radiance.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <optional>

#include "cpu_reference.h"
#include "image_stats.h"
#include "reference/path_tracer.h"
#include "render/obstacle_bvh.h"
#include "render/obstacle_meshes.h"
#include "render/obstacle_pass.h"
#include "support/scene_parts.h"
#include "test_volumes.h"

namespace sixway::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kSize = 32;

// The slab [0, 1] × [0, 0.5] × [0, 1] of density 1.
CpuVolume slab() {
  return constantBox({16, 8, 16}, 1.0f / 16, 1.0f);
}

scene::Smoke slabOptics() {
  scene::Smoke smoke;
  smoke.extinction = 3.0f;  // optical depth 1.5 from top to bottom, 3 front to back
  smoke.albedo = 0.8f;
  smoke.phaseG = 0.0f;  // isotropic: 1 / 4π
  return smoke;
}

// The sun straight above, irradiance 1.
scene::Light sun(bool shadows) {
  return directionalLight({0.0f, 1.0f, 0.0f}, 1.0f, shadows);
}

std::optional<double> hitSphere(dvec3 o, dvec3 d, dvec3 c, double r) {
  const dvec3 oc = o - c;
  const double b = glm::dot(oc, d), disc = b * b - (glm::dot(oc, oc) - r * r);
  if (disc < 0) return std::nullopt;
  const double t = -b - std::sqrt(disc);
  return t > 0 ? std::optional(t) : std::nullopt;
}

class PathTracerObstacleTest : public RenderTest {
 protected:
  io::Image trace(const CpuVolume& volume, const render::Camera& camera, const render::ImagePlane& plane,
                  const std::vector<scene::Light>& lights, const render::ObstacleBvh& obstacles,
                  uint32_t seed, uint32_t samples) {
    const render::DeviceVolume device = upload(volume);
    reference::TraceSettings s;
    s.width = s.height = kSize;
    s.maxOrders = 1;
    s.jitter = false;
    s.samplesPerPass = 64;
    s.seed = seed;
    tracer_.beginImage(device.view(), slabOptics(), camera, plane, lights, s, &obstacles);
    tracer_.accumulate(samples);
    return tracer_.image();
  }
  reference::PathTracer tracer_{context(), pipelineCache()};
};

// The slab seen edge-on from the front (+z), a sphere of radius 0.2 above its middle: single scattering with
// and without the sphere's shadow (the light's own flag) against the integral along each camera ray, within
// 3× the measured Monte Carlo error; the columns whose rays cross the shadow are darker by the analytic
// amount.
TEST_F(PathTracerObstacleTest, SphereShadowsTheSlabAsItsShadowCylinder) {
  const CpuVolume volume = slab();
  const glm::dvec3 centre(0.5, 1.2, 0.5);
  const double radius = 0.2;
  const render::ObstacleBvh sphere(context(), {sphereAt(glm::vec3(centre), float(radius))});
  const render::Camera camera =
      render::Camera::lookAt({0.5f, 0.25f, 3.0f}, {0.5f, 0.25f, 0.5f}, {0.0f, 1.0f, 0.0f}, 30.0f);
  const render::ImagePlane plane = squareBillboard(camera, volume.box());
  const scene::Smoke smoke = slabOptics();
  const double sigma = smoke.extinction, scatter = smoke.albedo * sigma / (4 * kPi);

  for (const bool shadows : {true, false}) {
    SCOPED_TRACE(shadows ? "obstacle shadows" : "the light casts none");
    const TwoSeeds traced =
        meanOfTwoSeeds(trace(volume, camera, plane, {sun(shadows)}, sphere, 1, 2048),
                       trace(volume, camera, plane, {sun(shadows)}, sphere, 2, 2048), {0});
    io::Image expected(kSize, kSize, {"R"});
    double shadowed = 0, open = 0;  // expected radiance summed over the columns crossing the shadow, and not
    double tracedShadowed = 0, tracedOpen = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const dvec3 d = cameraRay(camera, plane, {x + 0.5, y + 0.5}, kSize, kSize);
        const dvec3 o(camera.position);
        ASSERT_FALSE(hitSphere(o, d, centre, radius)) << "the sphere is out of view";
        const auto [t0, t1] = rayBox(o, d, volume.box());
        double sum = 0;
        constexpr int kSteps = 4000;
        for (int i = 0; i < kSteps && t1 > t0; ++i) {
          const double t = t0 + (i + 0.5) * (t1 - t0) / kSteps;
          const dvec3 p = o + t * d;
          const double horizontal = glm::length(glm::dvec2(p.x - centre.x, p.z - centre.z));
          if (shadows && horizontal < radius) continue;
          sum += scatter * std::exp(-sigma * (0.5 - p.y)) * std::exp(-sigma * (t - t0)) * (t1 - t0) / kSteps;
        }
        expected.at(x, y, 0) = float(sum);
        const double column = glm::dot(o + t0 * d - centre, dvec3(1, 0, 0));
        if (t1 <= t0 || std::abs(std::abs(column) - radius) < 0.05) continue;  // at the shadow's edge
        (std::abs(column) < radius ? shadowed : open) += sum;
        (std::abs(column) < radius ? tracedShadowed : tracedOpen) += traced.mean.at(x, y, 0);
      }
    EXPECT_GT(peak(expected, 0), 0.02);
    EXPECT_LT(traced.noise, 0.05 * peak(expected, 0)) << "enough samples";
    RecordProperty(shadows ? "rms_shadowed" : "rms_open", std::to_string(rms(traced.mean, expected, {0})));
    EXPECT_LT(rms(traced.mean, expected, {0}), 3 * traced.noise);
    // Whole columns: the shadowed ones hold this fraction of the open ones' light.
    EXPECT_NEAR(tracedShadowed / tracedOpen, shadowed / open, 0.03 * shadowed / open);
    if (shadows) {
      EXPECT_LT(shadowed / open, 0.8) << "the shadow must matter";
    }
  }
}

// A sphere of radius 0.2 under the slab, seen from the side below it: every pixel on the sphere is opaque
// and shows albedo/π · E · cos θ · exp(−σ_t · 0.5), the sun's light through the whole slab (ratio-tracked:
// within 5 binomial standard deviations).
TEST_F(PathTracerObstacleTest, SphereUnderTheSlabIsLitThroughIt) {
  const CpuVolume volume = slab();
  const glm::dvec3 centre(0.5, -0.45, 0.5);
  const double radius = 0.2;
  const render::ObstacleBvh sphere(context(), {sphereAt(glm::vec3(centre), float(radius))});
  const render::Camera camera =
      render::Camera::lookAt({0.5f, -0.45f, 3.0f}, {0.5f, -0.45f, 0.5f}, {0.0f, 1.0f, 0.0f}, 12.0f);
  const render::ImagePlane plane = render::fullFrame(camera, kSize, kSize);
  const uint32_t n = 2048;
  const io::Image image = trace(volume, camera, plane, {sun(true)}, sphere, 3, n);
  const double transmittance = std::exp(-slabOptics().extinction * 0.5);
  const double lambert = render::kObstacleAlbedo.x / kPi;
  int onSphere = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const dvec3 o(camera.position), d = cameraRay(camera, plane, {x + 0.5, y + 0.5}, kSize, kSize);
      const auto t = hitSphere(o, d, centre, radius);
      if (t.has_value() != hitSphere(o, d, centre, radius - render::sphereFacetDepth(radius)).has_value())
        continue;
      if (!t) continue;
      ++onSphere;
      EXPECT_EQ(image.at(x, y, 3), 1.0f) << x << "," << y;
      const double cosine = std::max(0.0, glm::normalize(o + *t * d - centre).y);
      const double expected = lambert * cosine * transmittance;
      const double tolerance = 5 * lambert * cosine * std::sqrt(transmittance * (1 - transmittance) / n) +
                               0.01 * lambert;  // the facets' normals
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.at(x, y, c), expected, tolerance) << x << "," << y;
    }
  EXPECT_GT(onSphere, 200);
}

// A sphere half inside a slab of smoke that absorbs and does not scatter (albedo 0), seen through the smoke
// and lit through it from above and behind: every pixel on the sphere shows the Lambertian radiance times the
// transmittance of the camera's chord and of the light's chord through the slab, each from the surface point
// (inside the smoke or not); within 5 binomial standard deviations of the product of the two.
TEST_F(PathTracerObstacleTest, SphereInsideAbsorbingSmoke) {
  const CpuVolume volume = slab();
  const glm::dvec3 centre(0.5, 0.45, 0.5);
  const double radius = 0.25;
  const render::ObstacleBvh sphere(context(), {sphereAt(glm::vec3(centre), float(radius))});
  const render::Camera camera =
      render::Camera::lookAt({0.5f, 0.55f, 3.0f}, {0.5f, 0.45f, 0.5f}, {0.0f, 1.0f, 0.0f}, 14.0f);
  const render::ImagePlane plane = render::fullFrame(camera, kSize, kSize);
  scene::Smoke smoke = slabOptics();
  smoke.albedo = 0.0f;
  const dvec3 toLight = glm::normalize(dvec3(0.0, 1.0, 0.6));
  const scene::Light light = directionalLight(glm::vec3(toLight), 1.0f);
  const render::DeviceVolume device = upload(volume);
  reference::TraceSettings s;
  s.width = s.height = kSize;
  s.maxOrders = 1;
  s.jitter = false;
  s.samplesPerPass = 64;
  const uint32_t n = 4096;
  tracer_.beginImage(device.view(), smoke, camera, plane, {light}, s, &sphere);
  tracer_.accumulate(n);
  const io::Image image = tracer_.image();
  const double lambert = render::kObstacleAlbedo.x / kPi;
  const auto chord = [&](dvec3 p, dvec3 d) {
    const auto [t0, t1] = rayBox(p, d, volume.box());
    return std::max(0.0, t1 - std::max(0.0, t0));
  };
  int inside = 0, onSphere = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const dvec3 o(camera.position), d = cameraRay(camera, plane, {x + 0.5, y + 0.5}, kSize, kSize);
      const auto t = hitSphere(o, d, centre, radius);
      if (t.has_value() != hitSphere(o, d, centre, radius - render::sphereFacetDepth(radius)).has_value())
        continue;
      if (!t) continue;
      const dvec3 p = o + *t * d, normal = glm::normalize(p - centre);
      const double cosine = glm::dot(normal, toLight);
      if (cosine < 0.1) continue;
      ++onSphere;
      inside += p.y < 0.5 && p.z < 1.0;
      const double camera = std::exp(-smoke.extinction * chord(p, -d)),
                   lit = std::exp(-smoke.extinction * chord(p, toLight));
      const double q = camera * lit, expected = lambert * cosine * q;
      EXPECT_EQ(image.at(x, y, 3), 1.0f) << x << "," << y;
      EXPECT_NEAR(image.at(x, y, 0), expected,
                  5 * lambert * cosine * std::sqrt(q * (1 - q) / n) + 0.01 * lambert)
          << x << "," << y;
    }
  EXPECT_GT(onSphere, 100);
  EXPECT_GT(inside, 50) << "surface points inside the smoke";
}

}  // namespace
}  // namespace sixway::test
