// The engine's frame time consumed by fixed lattice steps (SmokeSimulation::record with seconds): the same
// simulated time at a slow and a fast frame rate gives the same smoke, bit for bit; a frame longer than the
// cap simulates the cap and drops the rest; bad times and caps are refused.
#include <gtest/gtest.h>
#include <sixway/device.h>
#include <sixway/smoke_simulation.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "gpu/buffer.h"
#include "runtime/engine_harness.h"
#include "runtime/scene_volumes.h"
#include "support/temp_dir.h"

namespace sixway::test {
namespace {

// Records frames of `frameSeconds` each until `steps` lattice steps are simulated; the steps each frame took.
std::vector<uint32_t> simulate(BorrowingEngine& engine, SmokeSimulation& simulation, double frameSeconds,
                               uint32_t steps) {
  std::vector<uint32_t> taken;
  uint32_t done = 0;
  for (uint64_t frame = 0; done < steps; ++frame) {
    VkCommandBuffer commands = engine.begin();
    taken.push_back(simulation.record(commands, frame, frameSeconds));
    done += taken.back();
    engine.submitAndWait();
  }
  return taken;
}

std::vector<float> density(const SmokeSimulation& simulation) {
  return runtime::Access::volumes(simulation).currentVolume().density->download<float>();
}

TEST(FrameTime, TheSmokeMovesAtTheSameSpeedAtAnyFrameRate) {
  TempDir dir;
  const std::filesystem::path scene = sceneWithoutObstacles(dir.path());
  Device own({.validate = true});
  BorrowingEngine engine(own);
  SmokeSimulation slow(engine.device, scene), fast(engine.device, scene);
  const double step = slow.stepSeconds();
  constexpr uint32_t kSteps = 48;

  // Frames of eight steps each.
  for (uint32_t taken : simulate(engine, slow, 8 * step, kSteps)) EXPECT_EQ(taken, 8u);
  // Frames of three quarters of a step: three steps every four frames, one frame in four without one.
  const std::vector<uint32_t> fastSteps = simulate(engine, fast, 0.75 * step, kSteps);
  EXPECT_EQ(fastSteps.size(), 64u);
  EXPECT_EQ(std::count(fastSteps.begin(), fastSteps.end(), 0u), 16) << "frames without a step";

  EXPECT_DOUBLE_EQ(fast.seconds(), slow.seconds());
  // The scene's frames (its camera and light paths) follow the simulated time, not the records.
  EXPECT_EQ(fast.framesSimulated(), slow.framesSimulated());
  EXPECT_EQ(fast.framesSimulated(), int(std::floor(fast.seconds() / 0.1 + 1e-4))) << "small_plume's frame_dt";
  const std::vector<float> a = density(slow), b = density(fast);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_GT(*std::max_element(a.begin(), a.end()), 0.0f) << "no smoke yet";
  EXPECT_EQ(a, b) << "the same simulated time gave different smoke";
  EXPECT_EQ(own.validationMessages(), 0u);
}

TEST(FrameTime, ALongFrameSimulatesTheCapAndDropsTheRest) {
  TempDir dir;
  const std::filesystem::path scene = sceneWithoutObstacles(dir.path());
  Device own({.validate = true});
  BorrowingEngine engine(own);
  SmokeSimulation simulation(engine.device, scene);
  const double step = simulation.stepSeconds();
  simulation.setMaxStepsPerRecord(3);
  for (uint64_t frame = 0; frame < 3; ++frame) {
    VkCommandBuffer commands = engine.begin();
    EXPECT_EQ(simulation.record(commands, frame, 10.5 * step), 3u);
    engine.submitAndWait();
  }
  EXPECT_NEAR(simulation.seconds(), 9 * step, 1e-9) << "the time beyond the cap was not dropped";

  VkCommandBuffer commands = engine.begin();
  EXPECT_THROW(simulation.record(commands, 3, -0.01), std::invalid_argument);
  EXPECT_THROW(simulation.record(commands, 3, std::numeric_limits<double>::quiet_NaN()),
               std::invalid_argument);
  EXPECT_THROW(simulation.record(commands, 3, std::numeric_limits<double>::infinity()),
               std::invalid_argument);
  EXPECT_EQ(simulation.record(commands, 3, 0.0), 0u);
  engine.submitAndWait();
  EXPECT_THROW(simulation.setMaxStepsPerRecord(0), std::invalid_argument);
  EXPECT_THROW(simulation.setMaxStepsPerRecord(simulation.stepCapacity() + 1), std::invalid_argument);
  EXPECT_EQ(own.validationMessages(), 0u);
}

}  // namespace
}  // namespace sixway::test
