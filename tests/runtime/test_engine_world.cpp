// The world from the engine, each frame: emitters given in the world (through the instance's placement)
// make the same smoke as the same emitters given in the scene, and replace the scene's inlets; an obstacle
// steered with the engine's frame time arrives when asked, or at the speed limit when asked too much.
#include <gtest/gtest.h>
#include <sixway/device.h>
#include <sixway/smoke_simulation.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>
#include <vector>

#include "gpu/buffer.h"
#include "runtime/engine_harness.h"
#include "runtime/scene_volumes.h"
#include "support/temp_dir.h"

namespace sixway::test {
namespace {

std::vector<float> density(const SmokeSimulation& simulation) {
  return runtime::Access::volumes(simulation).currentVolume().density->download<float>();
}

double total(const std::vector<float>& values) {
  double sum = 0;
  for (float v : values) sum += v;
  return sum;
}

void recordSeconds(BorrowingEngine& engine, SmokeSimulation& simulation, uint64_t& frame, double seconds) {
  simulation.record(engine.begin(), frame++, seconds);
  engine.submitAndWait();
}

// A jet and a still source, on for four frames, the still one off for four more, given in the world of
// `placement`.
std::vector<float> emitted(BorrowingEngine& engine, const std::filesystem::path& scene,
                           const glm::mat4& placement) {
  SmokeSimulation simulation(engine.device, scene);
  simulation.setPlacement(placement);
  const auto world = [&](glm::vec3 p, float w) { return glm::vec3(placement * glm::vec4(p, w)); };
  std::vector<Emitter> emitters = {
      {.position = world({-0.13f, 0.23f, 0.05f}, 1), .radius = 0.09f, .velocity = world({0, 0.4f, 0.1f}, 0)},
      {.position = world({0.163f, 0.507f, -0.093f}, 1),
       .radius = 0.07f,
       .densityRate = 3.0f,
       .temperatureRate = 1}};
  uint64_t frame = 0;
  for (int f = 0; f < 8; ++f) {
    emitters[1].on = f < 4;
    simulation.setEmitters(emitters);
    recordSeconds(engine, simulation, frame, 0.1);
  }
  return density(simulation);
}

TEST(EngineWorld, EmittersInThePlacedWorldMakeTheSameSmoke) {
  TempDir dir;
  const std::filesystem::path scene = sceneWithoutObstacles(dir.path());
  Device own({.validate = true});
  BorrowingEngine engine(own);
  const std::vector<float> home = emitted(engine, scene, glm::mat4(1.0f));
  const glm::mat4 placement = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(-4.0f, 0.5f, 9.0f)),
                                          glm::radians(-35.0f), glm::vec3(0.0f, 1.0f, 0.0f));
  const std::vector<float> placed = emitted(engine, scene, placement);
  EXPECT_GT(total(home), 10.0) << "no smoke emitted";
  // The balls' cells are the same ones (no cell centre lies within 1e-3 cells of a ball's surface; the
  // placement's round trip moves a centre by ~1e-7 m), and the jet's direction differs by float rounding.
  EXPECT_LT(maxDifference(placed, home), 1e-5);

  // The scene's own inlets make other smoke; with no emitters there is none at all.
  SmokeSimulation inlets(engine.device, scene), none(engine.device, scene);
  none.setEmitters({});
  uint64_t frame = 0;
  for (int f = 0; f < 8; ++f) {
    recordSeconds(engine, inlets, frame, 0.1);
    recordSeconds(engine, none, frame, 0.1);
  }
  EXPECT_GT(maxDifference(density(inlets), home), 0.1);
  EXPECT_EQ(total(density(none)), 0.0);
  EXPECT_EQ(own.validationMessages(), 0u);
}

TEST(EngineWorld, AnObstacleSteeredWithTheFrameTimeArrivesThen) {
  Device own({.validate = true});
  BorrowingEngine engine(own);
  SmokeSimulation simulation(engine.device, kScene);
  const glm::mat4 placement = glm::translate(glm::mat4(1.0f), glm::vec3(2.0f, 0.0f, -1.0f));
  simulation.setPlacement(placement);
  const glm::vec3 start = simulation.obstaclePosition(0);
  const float limit = simulation.maxObstacleSpeed();
  ASSERT_GT(limit, 0.0f);
  uint64_t frame = 0;
  // Within the limit: there after the frame time, whatever steps that takes.
  const glm::vec3 near = start + glm::vec3(0.5f * limit * 0.2f, 0.0f, 0.0f);
  simulation.steerObstacle(0, near, 0.2);
  recordSeconds(engine, simulation, frame, 0.1);
  EXPECT_LT(glm::length(simulation.obstaclePosition(0) - (start + near) * 0.5f), 2e-3f) << "half way";
  recordSeconds(engine, simulation, frame, 0.1);
  EXPECT_LT(glm::length(simulation.obstaclePosition(0) - near), 1e-5f);
  // Twice too fast: it lags, moving at the limit.
  const glm::vec3 far = near + glm::vec3(0.0f, 2.0f * limit * 0.1f, 0.0f);
  simulation.steerObstacle(0, far, 0.1);
  recordSeconds(engine, simulation, frame, 0.1);
  EXPECT_NEAR(glm::length(simulation.obstaclePosition(0) - near), limit * 0.1f, 0.02f * limit * 0.1f);
  recordSeconds(engine, simulation, frame, 0.1);
  EXPECT_LT(glm::length(simulation.obstaclePosition(0) - far), 1e-5f);
  EXPECT_THROW(simulation.steerObstacle(0, far, -0.1), std::invalid_argument);
  EXPECT_THROW(simulation.steerObstacle(1, far, 0.1), std::invalid_argument);
  EXPECT_THROW(simulation.steerObstacle(0, glm::vec3(0.0f, INFINITY, 0.0f), 0.1), std::invalid_argument);
  EXPECT_EQ(own.validationMessages(), 0u);
}

}  // namespace
}  // namespace sixway::test
