// A smoke instance placed in the engine's world (SmokeSimulation::setPlacement): seen by the camera and lit
// by the lights moved with it, it is the same image as the unplaced instance; its obstacles and lightmap
// corners are where the placement puts them; placements that are not upright and rigid are refused.
#include <gtest/gtest.h>
#include <sixway/device.h>
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>

#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>
#include <vector>

#include "runtime/engine_harness.h"

namespace sixway::test {
namespace {

const std::filesystem::path kPlume = std::filesystem::path(SIXWAY_TEST_DATA_DIR) / "scenes/small_plume.json";

glm::vec3 moved(const glm::mat4& m, glm::vec3 p, float w = 1.0f) {
  return glm::vec3(m * glm::vec4(p, w));
}

struct Instance {
  std::vector<float> image;
  LightmapTextures lightmaps;
  glm::vec3 obstacle;
};

// Three frames of small_plume seen by sceneCamera() and lit by a sun and a point light, everything moved by
// `placement`.
Instance render(Device& device, const glm::mat4& placement) {
  SmokeSimulation simulation(device, kPlume);
  simulation.setPlacement(placement);
  SmokeRenderer renderer(device, simulation, {.weights = kWeights});
  Camera camera = sceneCamera();
  camera.position = moved(placement, camera.position);
  camera.target = moved(placement, camera.target);
  camera.up = moved(placement, camera.up, 0.0f);
  renderer.setCamera(camera);
  Light sun{.direction = moved(placement, {0.4f, 1.0f, 0.3f}, 0.0f)};
  Light lamp{
      .kind = Light::Kind::Point, .position = moved(placement, {-0.6f, 0.5f, 0.6f}), .intensity = 2.0f};
  renderer.setLights({sun, lamp});
  for (int frame = 0; frame < 3; ++frame) simulation.advance();
  renderer.render();
  return {renderer.image(), renderer.lightmaps(), simulation.obstaclePosition(0)};
}

TEST(Placement, APlacedInstanceSeenAndLitFromThePlacedWorldIsTheSameSmoke) {
  Device device({.validate = true});
  const Instance home = render(device, glm::mat4(1.0f));
  const glm::mat4 placement = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(5.0f, 1.5f, -3.0f)),
                                          glm::radians(70.0f), glm::vec3(0.0f, 1.0f, 0.0f));
  const Instance placed = render(device, placement);
  ASSERT_EQ(placed.image.size(), home.image.size());
  EXPECT_GT(*std::max_element(home.image.begin(), home.image.end()), 0.2f) << "no smoke";
  EXPECT_LT(maxDifference(placed.image, home.image), 2e-3);
  EXPECT_LT(glm::length(placed.obstacle - moved(placement, home.obstacle)), 1e-4f);
  for (int c = 0; c < 4; ++c)
    EXPECT_LT(glm::length(placed.lightmaps.corners[c] - moved(placement, home.lightmaps.corners[c])), 1e-4f)
        << "corner " << c;
  EXPECT_EQ(device.validationMessages(), 0u);
}

TEST(Placement, OnlyUprightRigidPlacementsAreTaken) {
  Device device;
  SmokeSimulation simulation(device, kPlume);
  const glm::mat4 tilt = glm::rotate(glm::mat4(1.0f), 0.2f, glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_THROW(simulation.setPlacement(tilt), std::invalid_argument);
  EXPECT_THROW(simulation.setPlacement(glm::scale(glm::mat4(1.0f), glm::vec3(2.0f))), std::invalid_argument);
  EXPECT_THROW(simulation.setPlacement(glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f))),
               std::invalid_argument)
      << "a mirror";
  glm::mat4 projective(1.0f);
  projective[2][3] = -1.0f;
  EXPECT_THROW(simulation.setPlacement(projective), std::invalid_argument);
  glm::mat4 nan(1.0f);
  nan[3][0] = std::nanf("");
  EXPECT_THROW(simulation.setPlacement(nan), std::invalid_argument);
  const glm::mat4 yaw = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 2.0f, 3.0f)), 2.5f,
                                    glm::vec3(0.0f, 1.0f, 0.0f));
  simulation.setPlacement(yaw);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(simulation.placement()[c][r], yaw[c][r], 1e-6f);
}

}  // namespace
}  // namespace sixway::test
