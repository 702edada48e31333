// The band around the obstacles that `sixway eval --scene` measures apart (eval/obstacle_band.h), against
// closed forms: a sphere's footprint is the disc it projects to, grown by the radius; a sphere above a slab
// of smoke lit from straight above shadows the columns of the slab within its radius, and only for a light
// that casts shadows.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>

#include "eval/obstacle_band.h"
#include "render/camera.h"
#include "support/gpu_fixture.h"
#include "support/scene_parts.h"

namespace sixway::test {
namespace {

constexpr int kSize = 64;

scene::Light sunAbove(bool shadows) {
  return directionalLight({0.0f, 1.0f, 0.0f}, 1.0f, shadows);
}

// A slab [0, 1] × [0, 0.5] × [0, 1] of density 1 in cells of 1/16, or no smoke.
eval::HostDensity slab(float density) {
  eval::HostDensity d;
  d.grid.size = {16, 8, 16};
  d.grid.cellSize = 1.0f / 16;
  d.values.assign(16 * 8 * 16, density);
  return d;
}

class ObstacleBandTest : public GpuTest {};

// Seen from the front with no smoke: the band is the sphere's projected disc grown by 4 pixels (up to a pixel
// of the disc's tessellated edge).
TEST_F(ObstacleBandTest, FootprintGrownByTheRadius) {
  const glm::vec3 centre(0.0f, 0.0f, 0.0f);
  const float radius = 0.3f;
  const render::ObstacleBvh sphere(context(), {sphereAt(centre, radius)});
  const render::Camera camera = render::Camera::lookAt({0.0f, 0.0f, 3.0f}, centre, {0.0f, 1.0f, 0.0f}, 30.0f);
  const render::ImagePlane plane = render::fullFrame(camera, kSize, kSize);
  eval::BandSettings settings;
  settings.radius = 4;
  settings.extinction = 3.0f;
  const std::vector<uint8_t> band =
      eval::obstacleBand(sphere, camera, plane, kSize, kSize, {sunAbove(true)}, slab(0.0f), settings);
  // The disc's radius in pixels: the angle to the silhouette, over the pixel's angle at the centre.
  const double halfAngle = std::asin(radius / 3.0);
  const double pixelsPerUnit = kSize / (plane.max.x - plane.min.x);
  const double discPx = std::tan(halfAngle) * pixelsPerUnit;
  int inside = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const double r = std::hypot(x + 0.5 - kSize / 2.0, y + 0.5 - kSize / 2.0);
      if (r < discPx + settings.radius - 1.5) {
        EXPECT_EQ(band[size_t(y) * kSize + x], 1) << x << "," << y;
        ++inside;
      }
      if (r > discPx + settings.radius + 1.5) {
        EXPECT_EQ(band[size_t(y) * kSize + x], 0) << x << "," << y;
      }
    }
  EXPECT_GT(inside, 200);
}

// The slab seen edge-on, a sphere of radius 0.2 out of view above its middle, the sun straight above: the
// columns within the sphere's radius see shadowed smoke, the others none; a light that casts no shadows makes
// none.
TEST_F(ObstacleBandTest, ShadowedSmokeUnderTheSphere) {
  const render::ObstacleBvh sphere(context(), {sphereAt({0.5f, 1.4f, 0.5f}, 0.2f)});
  const render::Camera camera =
      render::Camera::lookAt({0.5f, 0.25f, 4.0f}, {0.5f, 0.25f, 0.5f}, {0.0f, 1.0f, 0.0f}, 20.0f);
  const render::ImagePlane plane = render::fullFrame(camera, kSize, kSize);
  eval::BandSettings settings;
  settings.radius = 2;
  settings.extinction = 3.0f;
  const eval::HostDensity smoke = slab(1.0f);
  const std::vector<uint8_t> band =
      eval::obstacleBand(sphere, camera, plane, kSize, kSize, {sunAbove(true)}, smoke, settings);
  int shadowed = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const glm::vec3 w = render::rayDirection(camera, plane, {x + 0.5f, y + 0.5f}, kSize, kSize);
      const float t = (1.0f - camera.position.z) / w.z;  // the slab's front face
      const glm::vec3 p = camera.position + t * w;
      if (p.y < 0.05f || p.y > 0.45f) continue;  // rays through the slab's face, away from its edges
      const float column = std::abs(p.x - 0.5f);
      if (column < 0.15f) {
        EXPECT_EQ(band[size_t(y) * kSize + x], 1) << x << "," << y;
        ++shadowed;
      }
      if (column > 0.25f) {
        EXPECT_EQ(band[size_t(y) * kSize + x], 0) << x << "," << y;
      }
    }
  EXPECT_GT(shadowed, 100);
  const std::vector<uint8_t> unlit =
      eval::obstacleBand(sphere, camera, plane, kSize, kSize, {sunAbove(false)}, smoke, settings);
  EXPECT_EQ(std::count(unlit.begin(), unlit.end(), uint8_t(1)), 0);
}

TEST(ObstacleBandRadius, EightPixelsAt512) {
  EXPECT_EQ(eval::bandRadius(512), 8);
  EXPECT_EQ(eval::bandRadius(256), 4);
  EXPECT_EQ(eval::bandRadius(64), 2);
}

}  // namespace
}  // namespace sixway::test
