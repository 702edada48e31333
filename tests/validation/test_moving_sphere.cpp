// Moving obstacles: a sphere started impulsively through still fluid and a fixed sphere met by an
// impulsively started uniform stream are the same flow seen from two frames (Galilean invariance),
// so their drag must agree (moving-wall bounce-back, refilled cells and the refilling force term). And cells
// swept by a moving obstacle neither create nor lose smoke.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "sim/simulation.h"
#include "support/gpu_fixture.h"
#include "validation/flow_scene.h"

namespace sixway::test {
namespace {

constexpr int kLength = 64, kWidth = 24;
constexpr double kSpeed = 0.05, kRadius = 3, kReynolds = 20;
constexpr uint32_t kSteps = 640, kAverageFrom = 240;

nlohmann::json sphere(double x, const nlohmann::json& motion = nullptr) {
  nlohmann::json s = {{"type", "sphere"}, {"center", {x, kWidth / 2.0, kWidth / 2.0}}, {"radius", kRadius}};
  if (!motion.is_null()) s["motion"] = motion;
  return s;
}

// Mean drag (x force, lattice units) over steps kAverageFrom..kSteps.
double meanDrag(sim::Simulation& simulation) {
  simulation.advance(kAverageFrom);
  double drag = 0;
  while (simulation.step() < kSteps) {
    simulation.advance(50);
    for (const auto& step : simulation.report().forces) drag += step[0].x;
  }
  return drag / (kSteps - kAverageFrom);
}

class MovingSphere : public GpuTest, public ::testing::WithParamInterface<std::string> {};

// Parameter: fluid.population_storage.
TEST_P(MovingSphere, DragMatchesAFixedSphereInAStream) {
  // A periodic box, so that the two runs are exactly one flow in two frames: the fluid at U past a
  // fixed sphere, and the sphere at −U through fluid at rest (in both the drag slowly takes momentum
  // out of the flow the same way).
  const double nu = kSpeed * 2 * kRadius / kReynolds;
  nlohmann::json fixedExtra = populationStorage(GetParam());
  fixedExtra["obstacles"] = {sphere(20)};
  scene::Scene fixedScene = latticeScene(kLength, kWidth, kWidth, nu, "periodic", fixedExtra);
  sim::Simulation fixed(context(), pipelineCache(), fixedScene);
  const size_t cells = size_t(kLength) * kWidth * kWidth;
  fixed.setFlow(std::vector<glm::vec3>(cells, glm::vec3(kSpeed, 0, 0)), std::vector<float>(cells, 1.0f));
  const double fixedDrag = meanDrag(fixed);

  const nlohmann::json motion = {
      {"keyframes",
       {{{"time", 0.0}, {"position", {52.0, kWidth / 2.0, kWidth / 2.0}}},
        {{"time", double(kSteps)}, {"position", {52.0 - kSpeed * kSteps, kWidth / 2.0, kWidth / 2.0}}}}}};
  nlohmann::json movingSphere = sphere(52, motion);
  movingSphere.erase("center");  // the keyframes place it
  nlohmann::json movingExtra = populationStorage(GetParam());
  movingExtra["obstacles"] = {movingSphere};
  scene::Scene movingScene = latticeScene(kLength, kWidth, kWidth, nu, "periodic", movingExtra);
  sim::Simulation moving(context(), pipelineCache(), movingScene);
  const double movingDrag = meanDrag(moving);

  RecordProperty("fixed_drag", std::to_string(fixedDrag));
  RecordProperty("moving_drag", std::to_string(movingDrag));
  EXPECT_GT(fixedDrag, 0);
  std::printf("%s: fixed drag %.6g, moving drag %.6g, ratio %.4f\n", GetParam().c_str(), fixedDrag,
              movingDrag, movingDrag / fixedDrag);
  EXPECT_NEAR(movingDrag / fixedDrag, 1.0, 0.05) << "fixed " << fixedDrag << ", moving " << movingDrag;
}

INSTANTIATE_TEST_SUITE_P(PopulationStorage, MovingSphere, ::testing::Values("fp32", "fp16"));

TEST_F(GpuTest, SweptCellsKeepTheSmokeMass) {
  // A closed box full of smoke; the sphere crosses it, covering and uncovering cells every step.
  const nlohmann::json motion = {{"keyframes",
                                  {{{"time", 0.0}, {"position", {8.0, 10.0, 10.0}}},
                                   {{"time", 300.0}, {"position", {32.0, 10.0, 10.0}}}}}};
  nlohmann::json movingSphere = sphere(8, motion);
  movingSphere.erase("center");
  scene::Scene scene = latticeScene(40, 20, 20, 0.05, "no_slip", {{"obstacles", {movingSphere}}});
  sim::Simulation simulation(context(), pipelineCache(), scene);
  const size_t cells = 40 * 20 * 20;
  std::vector<glm::vec2> smoke(cells);
  for (size_t i = 0; i < cells; ++i) smoke[i] = glm::vec2(1.0f + 0.5f * float(i % 7) / 7.0f, 0.0f);
  simulation.smoke().upload(smoke);
  double before = 0;
  for (const glm::vec2& s : smoke) before += s.x;
  simulation.advance(300);
  double after = 0;
  float lowest = 1e9f;
  for (const glm::vec2& s : simulation.smoke().download()) after += s.x, lowest = std::min(lowest, s.x);
  RecordProperty("relative_mass_change", std::to_string((after - before) / before));
  EXPECT_NEAR(after / before, 1.0, 1e-5) << "mass before " << before << ", after " << after;
  EXPECT_GE(lowest, 0.0f);
}

}  // namespace
}  // namespace sixway::test
