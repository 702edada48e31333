// An engine's view and projection matrices read as the real-time frame's camera, image plane and depth map,
// against the matrices themselves: every world point in front of the camera lands on the image plane where
// the projection puts it, and its depth-buffer value maps back to its view depth (CPU only).
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <stdexcept>
#include <string>

#include "render/engine_view.h"
#include "support/engine_projections.h"

namespace sixway::test {
namespace {

constexpr float kNear = 0.1f, kFar = 50.0f, kFov = 0.8f, kAspect = 1.5f;

struct Case {
  std::string name;
  glm::mat4 view, projection;
};

std::vector<Case> cases() {
  const glm::vec3 eye(1.0f, 2.0f, 3.0f), target(-0.5f, 0.5f, 0.0f), up(0.0f, 1.0f, 0.0f);
  const glm::mat4 rh = glm::lookAtRH(eye, target, up), lh = glm::lookAtLH(eye, target, up);
  glm::mat4 jittered = vulkanY(glm::perspectiveRH_ZO(kFov, kAspect, kNear, kFar));
  jittered[2][0] += 0.37f / 640.0f;  // TAA: a sub-pixel offset in NDC, times w
  jittered[2][1] -= 0.81f / 480.0f;
  auto projection = [](DepthConvention convention) {
    return engineProjection(convention, kFov, kAspect, kNear, kFar);
  };
  return {{"standard", rh, projection(DepthConvention::Standard)},
          {"reversed", rh, projection(DepthConvention::Reversed)},
          {"infinite reversed", rh, projection(DepthConvention::InfiniteReversed)},
          {"infinite standard", rh, projection(DepthConvention::InfiniteStandard)},
          {"left-handed", lh, vulkanY(glm::perspectiveLH_ZO(kFov, kAspect, kNear, kFar))},
          {"jittered", rh, jittered},
          {"off-centre", rh, vulkanY(glm::frustumRH_ZO(-0.02f, 0.09f, -0.05f, 0.03f, kNear, kFar))},
          {"scaled", rh, 3.0f * vulkanY(glm::perspectiveRH_ZO(kFov, kAspect, kNear, kFar))}};
}

TEST(EngineView, PointsLandWhereTheProjectionPutsThemAtTheirDepth) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const render::EngineView ev = render::engineView(c.view, c.projection);
    const render::Camera& cam = ev.camera;
    EXPECT_NEAR(glm::length(glm::cross(cam.right, cam.up) + cam.forward), 0.0f, 1e-5f);  // the frame's axes
    EXPECT_NEAR(glm::length(cam.position - glm::vec3(1.0f, 2.0f, 3.0f)), 0.0f, 1e-5f);
    for (int i = 0; i < 200; ++i) {
      const glm::vec3 p =
          glm::vec3(-0.5f, 0.5f, 0.0f) + 4.0f * glm::vec3(unit(random), unit(random), unit(random));
      const glm::vec4 clip = c.projection * c.view * glm::vec4(p, 1.0f);
      if (clip.w <= kNear) continue;
      const glm::vec3 ndc = glm::vec3(clip) / clip.w;
      // The point on the image plane at view depth 1, and where the plane puts that NDC position.
      const glm::vec3 rel = p - cam.position;
      const float viewDepth = glm::dot(rel, cam.forward);
      const glm::vec2 q(glm::dot(rel, cam.right) / viewDepth, glm::dot(rel, cam.up) / viewDepth);
      const glm::vec2 expected(glm::mix(ev.plane.min.x, ev.plane.max.x, 0.5f * (ndc.x + 1.0f)),
                               glm::mix(ev.plane.max.y, ev.plane.min.y, 0.5f * (ndc.y + 1.0f)));
      EXPECT_NEAR(q.x, expected.x, 1e-4f * (1.0f + std::abs(q.x)));
      EXPECT_NEAR(q.y, expected.y, 1e-4f * (1.0f + std::abs(q.y)));
      EXPECT_NEAR(viewDepth, clip.w / std::abs(c.projection[2][3]), 1e-4f * viewDepth);
      EXPECT_NEAR(ndc.z, ev.depth.offset + ev.depth.scale / viewDepth, 2e-6f);
    }
  }
}

TEST(EngineView, TheLookAtCameraIsTheStandardProjection) {
  const render::Camera camera = render::Camera::lookAt({0, 1, 4}, {0, 1, 0}, {0, 1, 0}, 40.0f);
  const render::ImagePlane plane = render::fullFrame(camera, 300, 200);
  const glm::mat4 p = render::projectionMatrix(plane, {kNear, kFar});
  // sixway's own passes draw with a negative-height viewport (NDC y up); an engine's has y down.
  const render::EngineView ev = render::engineView(render::viewMatrix(camera), vulkanY(p));
  EXPECT_NEAR(glm::length(ev.camera.forward - camera.forward), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(ev.camera.right - camera.right), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(ev.plane.min - plane.min), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(ev.plane.max - plane.max), 0.0f, 1e-6f);
  const render::DepthMapping m = render::depthMapping({kNear, kFar});
  EXPECT_NEAR(ev.depth.offset, m.offset, 1e-6f);
  EXPECT_NEAR(ev.depth.scale, m.scale, 1e-7f);
}

TEST(EngineView, RefusesWhatItCannotReadAsAPerspective) {
  const glm::mat4 view = glm::lookAtRH(glm::vec3(0, 0, 3), glm::vec3(0), glm::vec3(0, 1, 0));
  const glm::mat4 perspective = vulkanY(glm::perspectiveRH_ZO(kFov, kAspect, kNear, kFar));
  auto refusal = [](const glm::mat4& v, const glm::mat4& p) -> std::string {
    try {
      render::engineView(v, p);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_NE(refusal(view, glm::orthoRH_ZO(-1.f, 1.f, -1.f, 1.f, kNear, kFar)).find("not a perspective"),
            std::string::npos);
  EXPECT_NE(refusal(view, glm::perspectiveRH_ZO(kFov, kAspect, kNear, kFar)).find("negative-height"),
            std::string::npos);
  EXPECT_NE(refusal(glm::scale(view, glm::vec3(2.0f)), perspective).find("not a rotation"),
            std::string::npos);
  glm::mat4 skewed = perspective;
  skewed[1][0] = 0.3f;
  EXPECT_NE(refusal(view, skewed).find("skews"), std::string::npos);
  EXPECT_EQ(refusal(view, perspective), "accepted");
}

}  // namespace
}  // namespace sixway::test
