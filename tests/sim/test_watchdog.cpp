// The watchdog (sim::checkWatchdog on the GPU reductions of the speed and the smoke): a NaN or a
// runaway speed stops sim::Simulation::advance with one line that names the step and the cell. Which
// cell is expected comes from the CPU oracle run on the same initial state: after a step the NaN has
// streamed into the neighbours, and the fastest cell is where the flow has moved it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "cpu_simulation.h"
#include "scene_fixtures.h"
#include "sim/simulation.h"
#include "sim/watchdog.h"
#include "support/gpu_fixture.h"

namespace sixway::test {
namespace {

constexpr glm::ivec3 kSize{16, 12, 10};

std::string cellText(int cell, glm::ivec3 size, double cellSize) {
  const glm::ivec3 c = cellOf(cell, size);
  const glm::dvec3 p = (glm::dvec3(c) + 0.5) * cellSize;
  char text[128];
  std::snprintf(text, sizeof(text), "cell (%d, %d, %d) at (%.3g, %.3g, %.3g) m", c.x, c.y, c.z, p.x, p.y,
                p.z);
  return text;
}

class WatchdogTest : public GpuTest {
 protected:
  // The watchdog's message after one step from `velocity` (empty if it does not trip), and the CPU state.
  std::string firstStepMessage(const std::vector<glm::vec3>& velocity, CpuSimulation& cpu) {
    const scene::Scene scene = parseLatticeScene(latticeScene(kSize, 0.02));
    const std::vector<float> density(velocity.size(), 1.0f);
    sim::Simulation gpu(context(), pipelineCache(), scene);
    gpu.setFlow(velocity, density);
    cpu.setFlow(toDouble(velocity), toDouble(density));
    cpu.advance(1);
    try {
      gpu.advance(1);
    } catch (const sim::WatchdogError& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(WatchdogTest, NaNVelocityNamesTheStepAndTheFirstCell) {
  std::vector<glm::vec3> velocity = smoothVelocity(kSize, 0.03f, 21);
  velocity[cellIndex({7, 5, 4}, kSize)].x = std::numeric_limits<float>::quiet_NaN();
  CpuSimulation cpu(parseLatticeScene(latticeScene(kSize, 0.02)));
  const std::string message = firstStepMessage(velocity, cpu);

  int count = 0, first = -1;
  for (int c = 0; c < int(cpu.lbm().macro().size()); ++c) {
    if (!std::isnan(glm::length(glm::dvec3(cpu.lbm().macro()[c])))) continue;
    if (count++ == 0) first = c;
  }
  ASSERT_EQ(count, 19) << "the NaN cell and its 18 neighbours";
  EXPECT_EQ(message, "watchdog: by step 1, the velocity is NaN or infinite in 19 cells, first " +
                         cellText(first, kSize, 1.0));
}

TEST_F(WatchdogTest, RunawaySpeedNamesTheFastestCell) {
  // A jet of up to 0.6 cells/step along x around one cell, above the limit kMaxStableLatticeSpeed.
  const glm::dvec3 centre(8.5, 6.5, 5.5);
  std::vector<glm::vec3> velocity(size_t(kSize.x) * kSize.y * kSize.z);
  for (size_t c = 0; c < velocity.size(); ++c) {
    const glm::dvec3 d = glm::dvec3(cellOf(int(c), kSize)) + 0.5 - centre;
    velocity[c] = glm::vec3(0.6 * std::exp(-glm::dot(d, d) / 8), 0.02 * d.y, 0.0);
  }
  CpuSimulation cpu(parseLatticeScene(latticeScene(kSize, 0.02)));
  const std::string message = firstStepMessage(velocity, cpu);

  double fastest = 0, second = 0;
  int where = -1;
  for (int c = 0; c < int(cpu.lbm().macro().size()); ++c) {
    const double speed = glm::length(glm::dvec3(cpu.lbm().macro()[c]));
    if (speed > fastest) {
      second = fastest;
      fastest = speed;
      where = c;
    } else {
      second = std::max(second, speed);
    }
  }
  ASSERT_GT(fastest, sim::kMaxStableLatticeSpeed);
  ASSERT_GT(fastest - second, 1e-4) << "the fastest cell must be clear of float rounding";
  char speed[32];
  std::snprintf(speed, sizeof(speed), "%.3f", fastest);
  EXPECT_EQ(message, std::string("watchdog: by step 1, the lattice speed reached ") + speed +
                         " cells/step (stable limit 0.35) at " + cellText(where, kSize, 1.0) +
                         "; lower the inflow speed or fluid.max_lattice_velocity");
}

TEST(Watchdog, NaNSmokeNamesTheSmokeCell) {
  gpu::Stats speed{};
  speed.maxAbs = 0.1f;
  speed.firstNonFinite = 0xffffffffu;
  gpu::Stats smoke{};
  smoke.nonFinite = 3;
  const glm::ivec3 lattice{8, 6, 4}, smokeGrid = lattice * 2;
  smoke.firstNonFinite = uint32_t(cellIndex({5, 7, 3}, smokeGrid));
  const sim::WatchdogReport r =
      sim::checkWatchdog(speed, smoke, 42, lattice, smokeGrid, glm::vec3(-1, 0, 2), 0.5f);
  EXPECT_TRUE(r.tripped);
  // Smoke cells of 0.25 m from the origin (−1, 0, 2): cell (5, 7, 3) is centred at (0.375, 1.875, 2.875).
  EXPECT_EQ(r.message,
            "watchdog: by step 42, the smoke density is NaN or infinite in 3 cells, first cell (5, 7, 3) at "
            "(0.375, "
            "1.88, 2.88) m");
}

TEST(Watchdog, QuietBelowTheLimit) {
  gpu::Stats speed{}, smoke{};
  speed.maxAbs = sim::kMaxStableLatticeSpeed;
  speed.firstNonFinite = smoke.firstNonFinite = 0xffffffffu;
  const sim::WatchdogReport r = sim::checkWatchdog(speed, smoke, 1, {8, 8, 8}, {8, 8, 8}, glm::vec3(0), 1.0f);
  EXPECT_FALSE(r.tripped);
  EXPECT_TRUE(r.message.empty());
}

}  // namespace
}  // namespace sixway::test
