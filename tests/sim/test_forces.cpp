// shaders/sim/forces.comp against the CPU momentum exchange (cpu_lbm.h) on the same lattice state: the
// GPU's populations and macro state before a step, read back, and the CPU's cell flags of that step.
//
// Tolerance, per component: 1e-5 × Σ |link term| of that component. The GPU adds a few hundred float
// terms (each ~0.01..0.1) in subgroup sums and float atomics, in no fixed order: its rounding error is
// ~√n ε Σ|term| ≈ 1e-6 Σ|term|. One link missing or counted twice changes the sum by a whole term,
// ≥ 1e-3 Σ|term| on these grids.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "cpu_simulation.h"
#include "gpu_state.h"
#include "scene_fixtures.h"
#include "sim/simulation.h"
#include "sim/watchdog.h"
#include "support/gpu_fixture.h"

namespace sixway::test {
namespace {

using nlohmann::json;

constexpr glm::ivec3 kSize{16, 12, 10};
constexpr double kRelativeTolerance = 1e-5;

// The CPU's inputs of lattice step `step` (the flags carry which cells were solid the step before).
CpuStepInputs inputsOfStep(const CpuSimulation& cpu, int step) {
  CpuStepInputs in = cpu.inputsAt(0, std::vector<CellFlags>(cpu.flags().size()));
  for (int s = 1; s <= step; ++s) in = cpu.inputsAt(s, in.flags);
  return in;
}

bool linksAnUncoveredCell(const CpuStepInputs& in, glm::ivec3 size) {
  for (int c = 0; c < int(in.flags.size()); ++c) {
    if (!in.flags[c].uncovered()) continue;
    for (int i = 1; i < d3q19::kQ; ++i) {
      const glm::ivec3 n = cellOf(c, size) + d3q19::velocity(i);
      if (insideGrid(n, size) && in.flags[cellIndex(n, size)].solid()) return true;
    }
  }
  return false;
}

class ForcesTest : public GpuTest {
 protected:
  // Runs `before` steps, then one more, and compares the force that step reports on each obstacle.
  void expectForcesMatch(const json& sceneJson, int before) {
    const scene::Scene scene = parseLatticeScene(sceneJson);
    const glm::ivec3 n = scene.grid.size;
    const CpuSimulation cpu(scene);
    for (int s = 0; s <= before; ++s)
      ASSERT_GT(cpu.surfaceMargin(s), 1e-3) << "a cell centre lies on an obstacle's surface at step " << s;
    sim::Simulation gpu(context(), pipelineCache(), scene);
    gpu.setFlow(smoothVelocity(n, 0.05f, 3), smoothDensity(n, 0.01f, 4));
    gpu.advance(before);
    const CpuStepInputs in = inputsOfStep(cpu, before);
    const std::vector<d3q19::Populations> post = downloadPopulations(gpu.lbm(), before % 2);
    const std::vector<glm::vec4> macroFloat = gpu.lbm().macro().download<glm::vec4>();
    const std::vector<glm::dvec4> macro(macroFloat.begin(), macroFloat.end());
    const CpuLbmSettings settings = cpuLbmSettings(scene);
    const LinkForces expected = momentumExchange(settings, post, macro, in);
    try {
      gpu.advance(1);
    } catch (const sim::WatchdogError& e) {  // the forces of the step are reported before the watchdog
      ADD_FAILURE() << e.what();
    }
    ASSERT_EQ(gpu.obstacles().flags().download<uint32_t>(), encodeFlags(in.flags))
        << "the GPU's cell flags differ from the CPU's: see ObstacleFlagsTest";

    ASSERT_EQ(gpu.report().forces.size(), 1u);
    const std::vector<glm::vec3>& got = gpu.report().forces[0];
    ASSERT_EQ(got.size(), expected.force.size());
    for (size_t o = 0; o < got.size(); ++o) {
      for (int a = 0; a < 3; ++a) {
        const double tolerance = kRelativeTolerance * expected.magnitude[o][a];
        EXPECT_NEAR(got[o][a], expected.force[o][a], tolerance)
            << "obstacle " << o << ", component " << a << " (Σ|term| " << expected.magnitude[o][a] << ")";
        std::cout << "[ measured ] obstacle " << o << " axis " << a << ": GPU " << got[o][a] << ", CPU "
                  << expected.force[o][a] << ", |Δ|/Σ|term| "
                  << std::abs(got[o][a] - expected.force[o][a]) / expected.magnitude[o][a] << "\n";
      }
    }
    if (!settings.interpolatedBounceBack) return;
    // The rule must matter: half-way bounce-back of the same state gives forces 100 × the tolerance away.
    CpuLbmSettings halfWay = settings;
    halfWay.interpolatedBounceBack = false;
    const LinkForces other = momentumExchange(halfWay, post, macro, in);
    double effect = 0;
    for (size_t o = 0; o < got.size(); ++o)
      for (int a = 0; a < 3; ++a)
        effect =
            std::max(effect, std::abs(other.force[o][a] - expected.force[o][a]) / expected.magnitude[o][a]);
    EXPECT_GT(effect, 100 * kRelativeTolerance)
        << "interpolated and half-way bounce-back give the same forces";
    std::cout << "[ measured ] half-way vs interpolated: |Δ|/Σ|term| up to " << effect << "\n";
  }
};

json latticeSceneWith(const json& obstacles, const std::string& boundary = "half_way") {
  return latticeScene(kSize, 0.02,
                      {{"fluid", {{"body_force", {2e-4, 0.0, -1e-4}}, {"obstacle_boundary", boundary}}},
                       {"obstacles", obstacles}});
}

TEST_F(ForcesTest, StaticSphereAndBox) {
  const json obstacles = {{{"type", "sphere"}, {"center", {5.3, 6.2, 4.9}}, {"radius", 2.73}},
                          {{"type", "box"}, {"center", {11.6, 5.45, 5.3}}, {"size", {2.7, 4.3, 3.1}}}};
  expectForcesMatch(latticeSceneWith(obstacles), 3);
}

TEST_F(ForcesTest, MovingSphere) {
  // (0.15, −0.04, 0.03) cells per step: step 1 uncovers cells next to the sphere. The step refills those
  // cells instead of bouncing populations back there, so their own links carry no force, while their
  // neighbours' links to them still do.
  const json keyframes = {{{"time", -10.0}, {"position", {6.3, 7.0, 5.2}}},
                          {{"time", 100.0}, {"position", {22.8, 2.6, 8.5}}}};
  const json obstacles = {{{"type", "sphere"}, {"radius", 3.1}, {"motion", {{"keyframes", keyframes}}}}};
  const json scene = latticeSceneWith(obstacles);
  const int step = 1;
  ASSERT_TRUE(linksAnUncoveredCell(inputsOfStep(CpuSimulation(parseLatticeScene(scene)), step), kSize))
      << "the scene must put an uncovered cell next to the sphere";
  expectForcesMatch(scene, step);
}

TEST_F(ForcesTest, SphereCutByAPeriodicFace) {
  // Fluid cells at x = 15 bounce back from the solid cells at x = 0 across the periodic face.
  const json obstacles = {{{"type", "sphere"}, {"center", {0.7, 6.2, 4.9}}, {"radius", 2.6}}};
  expectForcesMatch(latticeSceneWith(obstacles), 1);
}

// Interpolated bounce-back (fluid.obstacle_boundary "interpolated"): the links' populations come from the
// same rule as the flow's (sim_bounce_back.glsl).
TEST_F(ForcesTest, InterpolatedStaticSphereTiltedCylinderAndBox) {
  const json obstacles = {{{"type", "sphere"}, {"center", {4.3, 3.7, 4.9}}, {"radius", 2.23}},
                          {{"type", "cylinder"},
                           {"center", {5.17, 8.6, 5.3}},
                           {"radius", 1.7},
                           {"height", 3.6},
                           {"axis", {1.0, 0.2, -0.3}}},
                          {{"type", "box"}, {"center", {11.6, 5.45, 5.3}}, {"size", {2.7, 4.3, 3.1}}}};
  expectForcesMatch(latticeSceneWith(obstacles, "interpolated"), 3);
}

TEST_F(ForcesTest, InterpolatedMovingSphere) {
  const json keyframes = {{{"time", -10.0}, {"position", {6.3, 7.0, 5.2}}},
                          {{"time", 100.0}, {"position", {22.8, 2.6, 8.5}}}};
  const json obstacles = {{{"type", "sphere"}, {"radius", 3.1}, {"motion", {{"keyframes", keyframes}}}}};
  expectForcesMatch(latticeSceneWith(obstacles, "interpolated"), 1);
}

TEST_F(ForcesTest, InterpolatedSphereCutByAPeriodicFace) {
  const json obstacles = {{{"type", "sphere"}, {"center", {0.7, 6.2, 4.9}}, {"radius", 2.6}}};
  expectForcesMatch(latticeSceneWith(obstacles, "interpolated"), 1);
}

}  // namespace
}  // namespace sixway::test
