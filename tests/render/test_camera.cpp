// Cameras, image planes, billboards, the six-way frame, and scene paths (CPU only).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "render/billboard.h"
#include "render/camera.h"
#include "render/scene_frame.h"
#include "render/sixway.h"
#include "support/input_error.h"

namespace sixway::test {
namespace {

void expectVec(glm::vec3 a, glm::vec3 b, float tolerance = 1e-5f) {
  EXPECT_NEAR(glm::length(a - b), 0.0f, tolerance)
      << "(" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y << ", " << b.z << ")";
}

TEST(CameraTest, LookAtGivesARightHandedOrthonormalFrame) {
  const auto c = render::Camera::lookAt({1, 2, 3}, {-1, 0.5f, 0}, {0, 1, 0}, 50);
  expectVec(c.forward, glm::normalize(glm::vec3(-2, -1.5f, -3)));
  EXPECT_NEAR(glm::dot(c.right, c.up), 0, 1e-6);
  EXPECT_NEAR(glm::length(c.up), 1, 1e-6);
  expectVec(glm::cross(c.right, c.up), -c.forward);
  EXPECT_GT(c.up.y, 0);
  EXPECT_THROW(render::Camera::lookAt({0, 0, 0}, {0, 1, 0}, {0, 1, 0}, 40), std::invalid_argument);
}

// The default view looks down −z with +y up: Right is lit from +x, Back from −z (behind the smoke), Front
// from +z.
TEST(SixWayFrameTest, DefaultCameraLightsComeFromTheDocumentedWorldSides) {
  const render::Box box{{-1, 0, -1}, {1, 2, 1}};
  const auto c = render::framingCamera(box);
  expectVec(c.forward, {0, 0, -1});
  const auto d = render::sixWayLightDirections(c);
  expectVec(d[render::Right], {1, 0, 0});
  expectVec(d[render::Left], {-1, 0, 0});
  expectVec(d[render::Top], {0, 1, 0});
  expectVec(d[render::Bottom], {0, -1, 0});
  expectVec(d[render::Back], {0, 0, -1});
  expectVec(d[render::Front], {0, 0, 1});
  EXPECT_EQ(render::sixWayChannelNames()[render::Emissive], "emissive");
}

TEST(CameraTest, FramingCameraSeesTheWholeBox) {
  const render::Box box{{-0.3f, 0, 2}, {0.5f, 3, 2.4f}};
  const auto c = render::framingCamera(box, 40);
  const auto bounds = render::billboardBounds(c, box);
  const auto frame = render::fullFrame(c, 100, 100);
  EXPECT_GE(bounds.min.x, frame.min.x);
  EXPECT_GE(bounds.min.y, frame.min.y);
  EXPECT_LE(bounds.max.x, frame.max.x);
  EXPECT_LE(bounds.max.y, frame.max.y);
  expectVec(c.position, {0.1f, 1.5f, c.position.z});
  EXPECT_GT(c.position.z, box.max.z);
}

// Tight: every corner projects inside, and each side of the rectangle touches a corner. Widened: the aspect
// asked for, about the same centre, holding the tight one.
TEST(BillboardTest, IsTheProjectedBoxWidenedToTheAspect) {
  const render::Box box{{0, 0, 0}, {1, 2, 0.5f}};
  const auto c = render::Camera::lookAt({2.5f, 1.8f, 3}, {0.5f, 1, 0.2f}, {0, 1, 0}, 40);
  const auto tight = render::billboardBounds(c, box);
  glm::vec2 lo(1e9f), hi(-1e9f);
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 p((i & 1) ? 1 : 0, (i & 2) ? 2 : 0, (i & 4) ? 0.5f : 0);
    const glm::vec3 q = p - c.position;
    const glm::vec2 s(glm::dot(q, c.right) / glm::dot(q, c.forward),
                      glm::dot(q, c.up) / glm::dot(q, c.forward));
    lo = glm::min(lo, s);
    hi = glm::max(hi, s);
  }
  EXPECT_NEAR(tight.min.x, lo.x, 1e-6);
  EXPECT_NEAR(tight.max.y, hi.y, 1e-6);
  const auto wide = render::billboardBounds(c, box, 2.0f);
  EXPECT_NEAR((wide.max.x - wide.min.x) / (wide.max.y - wide.min.y), 2.0f, 1e-5);
  EXPECT_NEAR(wide.min.x + wide.max.x, tight.min.x + tight.max.x, 1e-6);
  EXPECT_LE(wide.min.y, tight.min.y);
  EXPECT_GE(wide.max.x, tight.max.x);
  // The corners at a depth project back onto the rectangle's corners.
  const auto corners = render::billboardCorners(c, wide, 3.0f);
  const glm::vec3 q = corners[2] - c.position;
  EXPECT_NEAR(glm::dot(q, c.right) / glm::dot(q, c.forward), wide.max.x, 1e-5);
  EXPECT_NEAR(glm::dot(q, c.forward), 3.0f, 1e-5);
}

TEST(BillboardTest, BoxBehindTheCameraIsAnError) {
  const auto c = render::Camera::lookAt({0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, -1}, {0, 1, 0}, 40);
  EXPECT_THAT(inputErrorMessage([&] {
                render::billboardBounds(c, {{0, 0, 0}, {1, 1, 1}});
              }),
              ::testing::HasSubstr("behind the camera"));
}

TEST(CameraTest, PixelCentreRayOfAFullFrameIsTheViewAxis) {
  const auto c = render::Camera::lookAt({0, 0, 5}, {1, 0, 0}, {0, 1, 0}, 60);
  expectVec(render::rayDirection(c, render::fullFrame(c, 9, 5), {4.5f, 2.5f}, 9, 5), c.forward);
  // Row 0 is the top: its rays lean up.
  EXPECT_GT(glm::dot(render::rayDirection(c, render::fullFrame(c, 9, 5), {4.5f, 0.5f}, 9, 5), c.up), 0.0f);
}

// Orbits turn counter-clockwise seen from above (right-hand rule about +y): +z goes to +x after 90°.
TEST(SceneFrameTest, OrbitsAndDolliesMoveAsTheSceneFormatSays) {
  scene::Camera camera;
  camera.position = {0, 1, 4};
  camera.target = {0, 1, 0};
  camera.path = scene::CameraOrbit{30.0f};
  expectVec(render::sceneCamera(camera, 3).position, {4, 1, 0}, 1e-4f);
  camera.path = scene::CameraDolly{{0, 1, 2}, 4};
  expectVec(render::sceneCamera(camera, 2).position, {0, 1, 3});
  expectVec(render::sceneCamera(camera, 9).position, {0, 1, 2});

  scene::Light lamp{scene::PointLight{{1, 0, 0}}};
  lamp.path = scene::LightOrbit{{0, 0, 0}, {0, 1, 0}, 90.0f};
  const auto moved = render::sceneLights({lamp}, 1);
  expectVec(std::get<scene::PointLight>(moved[0].source).position, {0, 0, -1});
  EXPECT_FALSE(moved[0].path.has_value());
}

}  // namespace
}  // namespace sixway::test
