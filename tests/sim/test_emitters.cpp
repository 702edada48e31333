// Emitters set from outside the scene file (sim::Simulation::setEmitters, an engine's each frame) against
// what they must do exactly: in a fluid at rest without buoyancy nothing moves, so every cell whose centre
// lies in the ball gains rate · dt per step and no other cell gains anything; a jet sets the flow there to
// its velocity; an emitter switched off adds nothing; moves inside the cells covered so far record nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "scene_fixtures.h"
#include "sim/simulation.h"
#include "support/gpu_fixture.h"

namespace sixway::test {
namespace {

using nlohmann::json;

constexpr glm::ivec3 kSize{16, 12, 10};

class EmitterTest : public GpuTest {
 protected:
  // Cells of 1 m and steps of 1 s (m/s are cells per step), walls all round, the fluid at rest.
  static scene::Scene scene() {
    json walls = json::object();
    for (const char* face : {"x-", "x+", "y-", "y+", "z-", "z+"}) walls[face] = "no_slip";
    return parseLatticeScene(latticeScene(kSize, 0.02, {{"boundaries", walls}}));
  }
};

// Whether cell i's centre lies within `radius` of `centre` (lattice coordinates).
std::vector<bool> ball(glm::dvec3 centre, double radius) {
  std::vector<bool> inside;
  for (int z = 0; z < kSize.z; ++z)
    for (int y = 0; y < kSize.y; ++y)
      for (int x = 0; x < kSize.x; ++x) {
        const glm::dvec3 d = glm::dvec3(x, y, z) + 0.5 - centre;
        inside.push_back(glm::dot(d, d) <= radius * radius);
      }
  return inside;
}

TEST_F(EmitterTest, ABallGainsItsRatesAndNothingElseMoves) {
  sim::Simulation simulation(context(), pipelineCache(), scene());
  const sim::Emitter emitter{
      .centre = {7.3f, 5.9f, 4.6f}, .radius = 2.6f, .densityRate = 0.25f, .temperatureRate = 0.5f};
  simulation.setEmitters(std::span(&emitter, 1));
  const int steps = 6;
  simulation.advance(steps);
  const std::vector<bool> inside = ball(glm::dvec3(emitter.centre), emitter.radius);
  const std::vector<glm::vec2> smoke = simulation.smoke().download();
  int cells = 0;
  for (size_t i = 0; i < smoke.size(); ++i) {
    const glm::vec2 expected = inside[i] ? glm::vec2(steps * 0.25f, steps * 0.5f) : glm::vec2(0.0f);
    ASSERT_NEAR(smoke[i].x, expected.x, 1e-6f) << "cell " << i;
    ASSERT_NEAR(smoke[i].y, expected.y, 1e-6f) << "cell " << i;
    cells += inside[i];
  }
  EXPECT_GT(cells, 50);
  for (const glm::vec4& m : simulation.lbm().macro().download<glm::vec4>())
    ASSERT_EQ(glm::vec3(m), glm::vec3(0.0f)) << "an emitter without velocity moved the fluid";

  // A jet sets the flow in its cells to its velocity (m/s = cells per step here).
  sim::Emitter jet = emitter;
  jet.velocity = {0.0f, 0.06f, 0.0f};
  simulation.setEmitters(std::span(&jet, 1));
  simulation.advance(1);
  const std::vector<glm::vec4> macro = simulation.lbm().macro().download<glm::vec4>();
  for (size_t i = 0; i < macro.size(); ++i)
    if (inside[i]) {
      ASSERT_NEAR(macro[i].y, 0.06f, 1e-7f) << "cell " << i;
    }

  // Switched off: the smoke only moves, its mass stays (walls all round, no dissipation).
  jet.on = false;
  simulation.setEmitters(std::span(&jet, 1));
  simulation.advance(1);
  const double mass = simulation.report().smokeMass;
  simulation.advance(4);
  EXPECT_NEAR(simulation.report().smokeMass, mass, 1e-5 * mass);
  EXPECT_NEAR(mass, (steps + 1) * 0.25 * cells, 1e-4 * mass) << "the mass the emitter added";
}

TEST_F(EmitterTest, MovesInsideTheCoveredCellsRecordNothingAgain) {
  sim::Simulation simulation(context(), pipelineCache(), scene());
  sim::Emitter emitter{.centre = {4.0f, 4.0f, 5.0f}, .radius = 1.5f, .densityRate = 1.0f};
  simulation.setEmitters(std::span(&emitter, 1));
  simulation.advance(2);  // one recorded sequence: two steps from an even step
  const uint64_t first = simulation.sequencesRecorded();
  emitter.centre.x = 12.0f;  // beyond the cells covered so far: recorded once more
  simulation.setEmitters(std::span(&emitter, 1));
  simulation.advance(2);
  EXPECT_EQ(simulation.sequencesRecorded(), first + 1);
  for (float x : {6.0f, 9.0f, 4.0f, 12.0f}) {  // back and forth within them
    emitter.centre.x = x;
    simulation.setEmitters(std::span(&emitter, 1));
    simulation.advance(2);
  }
  EXPECT_EQ(simulation.sequencesRecorded(), first + 1);
  // The emitter at x = 12 filled its ball there this step.
  const std::vector<glm::vec2> smoke = simulation.smoke().download();
  const std::vector<bool> inside = ball(glm::dvec3(emitter.centre), emitter.radius);
  for (size_t i = 0; i < smoke.size(); ++i)
    if (inside[i]) {
      ASSERT_GE(smoke[i].x, 1.0f - 1e-6f) << "cell " << i;
    }
}

TEST_F(EmitterTest, RefusesWhatTheLatticeCannotFollow) {
  sim::Simulation simulation(context(), pipelineCache(), scene());
  // fluid.max_lattice_velocity: 0.1 cells per step.
  EXPECT_NEAR(simulation.emitterSpeedLimit(), 0.1, 1e-6);
  const sim::Emitter fast{.centre = {8, 6, 5}, .radius = 1, .velocity = {0.0f, 0.11f, 0.0f}};
  EXPECT_THROW(simulation.setEmitters(std::span(&fast, 1)), std::invalid_argument);
  const sim::Emitter negative{.centre = {8, 6, 5}, .radius = -1};
  EXPECT_THROW(simulation.setEmitters(std::span(&negative, 1)), std::invalid_argument);
  const sim::Emitter notFinite{.centre = {8, 6, 5}, .radius = 1, .densityRate = NAN};
  EXPECT_THROW(simulation.setEmitters(std::span(&notFinite, 1)), std::invalid_argument);
  const sim::Emitter nowhere{.centre = {8, NAN, 5}, .radius = 1};
  EXPECT_THROW(simulation.setEmitters(std::span(&nowhere, 1)), std::invalid_argument);
  const std::vector<sim::Emitter> many(sim::kMaxInlets + 1, sim::Emitter{.centre = {8, 6, 5}, .radius = 1});
  EXPECT_THROW(simulation.setEmitters(many), std::invalid_argument);
}

}  // namespace
}  // namespace sixway::test
