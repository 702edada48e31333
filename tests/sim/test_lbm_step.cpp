// shaders/sim/lbm_step.comp (through sim::Simulation, with the obstacle flags and the smoke it drives)
// against the CPU oracle, a few steps on small grids from a smooth random flow.
//
// Tolerance: 1e-5 (cells/step) on each velocity component and on the density (ρ ≈ 1). The GPU works in
// float (ε = 6e-8), the oracle in double; a population (≤ 1/3) takes a few roundings per step and the
// moments sum 19 of them, so after 5 steps the expected difference is ~1e-7 to 1e-6. A real error in a
// boundary rule or a collision term shows up at the size of the term: u ≈ 0.05, forces ≈ 1e-4 per step.
// Each test also checks that the feature it covers changes the CPU result by more than 10 × the
// tolerance, so that the comparison cannot pass with the feature ignored.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cpu_simulation.h"
#include "scene_fixtures.h"
#include "sim/simulation.h"
#include "sim/watchdog.h"
#include "support/gpu_fixture.h"

namespace sixway::test {
namespace {

using nlohmann::json;

constexpr double kTolerance = 1e-5;
constexpr double kSurfaceMargin = 1e-3;  // cells; far beyond float rounding of the GPU's inside tests
constexpr glm::ivec3 kSize{16, 12, 10};
constexpr float kViscosity = 0.02f;  // τ = 0.56

struct Initial {
  std::vector<glm::vec3> velocity;
  std::vector<float> density;
  std::vector<glm::vec2> smoke;
};

Initial initialState(const scene::Scene& scene) {
  const glm::ivec3 n = scene.grid.size;
  return {smoothVelocity(n, 0.05f, 7), smoothDensity(n, 0.01f, 8), smoothSmoke(n * scene.grid.smokeUpres, 9)};
}

std::vector<glm::dvec4> cpuMacro(const scene::Scene& scene, int steps) {
  const Initial init = initialState(scene);
  CpuSimulation cpu(scene);
  cpu.setFlow(toDouble(init.velocity), toDouble(init.density));
  cpu.setSmoke(toDouble(init.smoke));
  cpu.advance(steps);
  return cpu.lbm().macro();
}

std::string describe(const FieldError& e, const scene::Scene& scene, const std::vector<glm::vec4>& gpu,
                     const std::vector<glm::dvec4>& cpu) {
  if (e.cell < 0) return "";
  const glm::vec4 g = gpu[e.cell];
  const glm::dvec4 c = cpu[e.cell];
  std::ostringstream out;
  out << " differs most at " << e.where(scene.grid.size) << ": GPU (u, rho) = (" << g.x << ", " << g.y << ", "
      << g.z << ", " << g.w << "), CPU (" << c.x << ", " << c.y << ", " << c.z << ", " << c.w << ")";
  return out.str();
}

class LbmStepTest : public GpuTest {
 protected:
  // Runs `steps` steps of `scene` on the GPU and the CPU and compares the velocity and density; the CPU
  // result of `withoutFeature` (the scene with the tested feature turned off) must differ clearly (by 10 ×
  // the tolerance).
  void expectMatchesCpu(const json& sceneJson, int steps, const json& withoutFeature,
                        double tolerance = kTolerance) {
    const scene::Scene scene = parseLatticeScene(sceneJson);
    const CpuSimulation probe(scene);
    for (int s = 0; s <= steps; ++s)
      ASSERT_GT(probe.surfaceMargin(s), kSurfaceMargin)
          << "a cell centre lies on an obstacle's surface at step " << s;
    const Initial init = initialState(scene);
    sim::Simulation gpu(context(), pipelineCache(), scene);
    gpu.setFlow(init.velocity, init.density);
    gpu.smoke().upload(init.smoke);
    try {
      gpu.advance(steps);
    } catch (const sim::WatchdogError& e) {
      FAIL() << "the GPU flow diverged where the CPU reference stays smooth: " << e.what();
    }
    const std::vector<glm::vec4> gpuMacro = gpu.lbm().macro().download<glm::vec4>();
    const std::vector<glm::dvec4> expected = cpuMacro(scene, steps);
    const uint64_t populationBytes = scene.fluid.populationStorage == scene::PopulationStorage::Fp16 ? 2 : 4;
    const glm::ivec3 stored = gpu.lbm().storedSize();
    EXPECT_EQ(gpu.lbm().lattice(0).size(), uint64_t(stored.x) * stored.y * stored.z * 5 * populationBytes)
        << "population storage";

    const FieldError u = velocityError(gpuMacro, expected), rho = densityError(gpuMacro, expected);
    EXPECT_LE(u.max, tolerance) << "velocity" << describe(u, scene, gpuMacro, expected);
    EXPECT_LE(rho.max, tolerance) << "density" << describe(rho, scene, gpuMacro, expected);
    const FieldError effect = maxDifference(expected, cpuMacro(parseLatticeScene(withoutFeature), steps));
    EXPECT_GT(effect.max, 10 * tolerance) << "the feature under test hardly changes the flow";
    std::cout << "[ measured ] max |Δu| " << u.max << ", max |Δρ| " << rho.max << "; feature effect "
              << effect.max << "\n";
  }
};

json withPatch(json scene, const json& patch) {
  scene.merge_patch(patch);
  return scene;
}

TEST_F(LbmStepTest, PeriodicBox) {
  const json scene = latticeScene(kSize, kViscosity);
  // Against a much more viscous fluid (τ = 3.5): the collision must shape the result.
  expectMatchesCpu(scene, 5, withPatch(scene, {{"fluid", {{"viscosity", 1.0}}}}));
}

// lbm_step runs as two dispatches, the interior and the cells next to faces and obstacles (cellVisited):
// on thin lattices too every cell must be updated exactly once. One cell deep between periodic faces (the
// quasi-2D validation runs: that axis has no boundary cells) with a cylinder across it; one cell deep
// between walls (a single face slab); two cells deep (no interior at all).
TEST_F(LbmStepTest, ThinLattices) {
  const json cylinder = {{"boundaries", {{"y-", "no_slip"}, {"y+", "no_slip"}}},
                         {"obstacles",
                          {{{"type", "cylinder"},
                            {"center", {6.3, 5.7, 0.5}},
                            {"radius", 2.2},
                            {"height", 4.0},
                            {"axis", {0.0, 0.0, 1.0}}}}}};
  const json walls = {{"boundaries", {{"z-", "no_slip"}, {"z+", "free_slip"}}}};
  for (const auto& [size, patch] :
       {std::pair{glm::ivec3(16, 12, 1), cylinder}, std::pair{glm::ivec3(16, 12, 1), walls},
        std::pair{glm::ivec3(16, 2, 10), walls}}) {
    SCOPED_TRACE(std::to_string(size.x) + "x" + std::to_string(size.y) + "x" + std::to_string(size.z));
    const json scene = latticeScene(size, kViscosity, patch);
    expectMatchesCpu(scene, 4, withPatch(scene, {{"fluid", {{"viscosity", 1.0}}}}));
  }
}

TEST_F(LbmStepTest, NoSlipAndFreeSlipWallsInAClosedBox) {
  const json walls = {{"boundaries",
                       {{"x-", "no_slip"},
                        {"x+", "free_slip"},
                        {"y-", "free_slip"},
                        {"y+", "no_slip"},
                        {"z-", "no_slip"},
                        {"z+", "free_slip"}}}};
  expectMatchesCpu(latticeScene(kSize, kViscosity, walls), 4, latticeScene(kSize, kViscosity));
}

TEST_F(LbmStepTest, FreeSlipWallsAlongAPeriodicAxis) {
  // At x = 0 and x = 15 a diagonal population reflected by a free-slip wall comes from the tangential
  // neighbour on the other side of the periodic x faces.
  const json walls = {
      {"boundaries", {{"y-", "free_slip"}, {"y+", "free_slip"}, {"z-", "no_slip"}, {"z+", "free_slip"}}}};
  expectMatchesCpu(latticeScene(kSize, kViscosity, walls), 4, latticeScene(kSize, kViscosity));
}

TEST_F(LbmStepTest, UniformInflowAndOutflow) {
  const json open = {{"boundaries", {{"x-", "inflow"}, {"x+", "outflow"}, {"wind", {0.06, 0.01, -0.02}}}}};
  expectMatchesCpu(latticeScene(kSize, kViscosity, open), 5, latticeScene(kSize, kViscosity));
}

TEST_F(LbmStepTest, ParabolicInflowInANoSlipChannel) {
  const json channel = {{"boundaries",
                         {{"x-", "inflow"},
                          {"x+", "outflow"},
                          {"y-", "no_slip"},
                          {"y+", "no_slip"},
                          {"z-", "no_slip"},
                          {"z+", "no_slip"},
                          {"wind", {0.08, 0.0, 0.0}},
                          {"inflow_profile", "parabolic"}}}};
  const json scene = latticeScene(kSize, kViscosity, channel);
  expectMatchesCpu(scene, 5, withPatch(scene, {{"boundaries", {{"inflow_profile", "uniform"}}}}));
}

TEST_F(LbmStepTest, StaticSphereBounceBack) {
  const json sphere = {{"obstacles", {{{"type", "sphere"}, {"center", {7.8, 6.3, 5.15}}, {"radius", 3.1}}}}};
  expectMatchesCpu(latticeScene(kSize, kViscosity, sphere), 5, latticeScene(kSize, kViscosity));
}

TEST_F(LbmStepTest, StaticSphereCutByAPeriodicFace) {
  // Fluid cells at x = 15 bounce back from the solid cells at x = 0 across the periodic face.
  const json sphere = {{"obstacles", {{{"type", "sphere"}, {"center", {0.7, 6.3, 5.15}}, {"radius", 2.6}}}}};
  expectMatchesCpu(latticeScene(kSize, kViscosity, sphere), 3, latticeScene(kSize, kViscosity));
}

TEST_F(LbmStepTest, MovingSphereBounceBackAndRefill) {
  // 0.12 cells per step along a diagonal: cells are covered and uncovered within the five steps. An
  // uncovered cell restarts from f^eq(1, u_wall); its neighbours still bounce back from the wall there.
  const glm::dvec3 start(7.8, 6.3, 5.15), velocity(0.12, -0.07, 0.05);
  const auto at = [&](double t) {
    const glm::dvec3 p = start + t * velocity;
    return json{p.x, p.y, p.z};
  };
  const json moving = {
      {"obstacles",
       {{{"type", "sphere"},
         {"radius", 3.1},
         {"motion",
          {{"keyframes",
            {{{"time", -10.0}, {"position", at(-10)}}, {{"time", 100.0}, {"position", at(100)}}}}}}}}}};
  const json scene = latticeScene(kSize, kViscosity, moving);
  const CpuSimulation probe(parseLatticeScene(scene));
  int uncovered = 0;
  CpuStepInputs in = probe.inputsAt(0, std::vector<CellFlags>(size_t(kSize.x) * kSize.y * kSize.z));
  for (int s = 1; s < 5; ++s) {
    in = probe.inputsAt(s, in.flags);
    for (const CellFlags& f : in.flags) uncovered += f.uncovered();
  }
  ASSERT_GT(uncovered, 0) << "the scene must uncover cells to test the refill";
  const json still = latticeScene(
      kSize, kViscosity, {{"obstacles", {{{"type", "sphere"}, {"center", at(0)}, {"radius", 3.1}}}}});
  expectMatchesCpu(scene, 5, still);
}

// Interpolated bounce-back (fluid.obstacle_boundary "interpolated"): each link to an obstacle ends where it
// crosses the analytic surface; against half-way bounce-back on the same obstacles.
json interpolated(const json& scene) {
  return withPatch(scene, {{"fluid", {{"obstacle_boundary", "interpolated"}}}});
}

// A sphere whose swept box stays off every face: the boundary cells then run as two pipelines, the face slabs
// without the bounce-back code and the box without the face conditions (LbmSolver::recordStep); the spheres
// above reach a face and take the one pipeline with both. Half-way and interpolated bounce-back.
TEST_F(LbmStepTest, SphereAwayFromTheFaces) {
  const glm::ivec3 size{20, 18, 16};
  const json sphere = {{"obstacles", {{{"type", "sphere"}, {"center", {10.2, 8.7, 7.9}}, {"radius", 3.1}}}}};
  for (const json& scene :
       {latticeScene(size, kViscosity, sphere), interpolated(latticeScene(size, kViscosity, sphere))})
    expectMatchesCpu(scene, 3, latticeScene(size, kViscosity));
}

TEST_F(LbmStepTest, InterpolatedBounceBackOnASphere) {
  const json sphere = {{"obstacles", {{{"type", "sphere"}, {"center", {7.8, 6.3, 5.15}}, {"radius", 3.1}}}}};
  const json halfWay = latticeScene(kSize, kViscosity, sphere);
  expectMatchesCpu(interpolated(halfWay), 5, halfWay);
}

TEST_F(LbmStepTest, InterpolatedBounceBackOnATiltedCylinderAndABox) {
  // The cylinder's links cross its side and its caps; the box's its faces, edges and corners.
  const json obstacles = {{"obstacles",
                           {{{"type", "cylinder"},
                             {"center", {5.13, 6.2, 5.3}},
                             {"radius", 2.2},
                             {"height", 5.0},
                             {"axis", {0.3, 1.0, 0.2}}},
                            {{"type", "box"}, {"center", {11.6, 5.45, 5.3}}, {"size", {2.7, 4.3, 3.1}}}}}};
  const json halfWay = latticeScene(kSize, kViscosity, obstacles);
  expectMatchesCpu(interpolated(halfWay), 5, halfWay);
}

TEST_F(LbmStepTest, InterpolatedBounceBackOnATiltedCapsule) {
  // Links cross its side and both caps (kSize is 16 × 12 × 10 cells).
  const json capsule = {{"obstacles",
                         {{{"type", "capsule"},
                           {"center", {8.13, 6.2, 5.3}},
                           {"radius", 2.3},
                           {"height", 8.6},
                           {"axis", {1.0, 0.4, 0.2}}}}}};
  const json halfWay = latticeScene(kSize, kViscosity, capsule);
  expectMatchesCpu(interpolated(halfWay), 5, halfWay);
}

TEST_F(LbmStepTest, InterpolatedBounceBackAcrossAPeriodicFace) {
  // Links from x = 15 to solid cells at x = 0 measure the wall from the fluid cell's periodic image.
  const json sphere = {{"obstacles", {{{"type", "sphere"}, {"center", {0.7, 6.3, 5.15}}, {"radius", 2.6}}}}};
  const json halfWay = latticeScene(kSize, kViscosity, sphere);
  expectMatchesCpu(interpolated(halfWay), 3, halfWay);
}

// 16-bit population storage (fluid.population_storage "fp16", lbm_lattice.glsl) against the same double
// oracle: each stored population is rounded to 11 significant bits of f_i − w_i (|f_i − w_i| ≲ 0.03 here, a
// rounding ≲ 1.5e-5 per population per step); measured ≤ 3.5e-5 after 5 steps, so the tolerance is 1e-4.
// Every boundary rule reads the populations through the same load, so a periodic box, walls with inflow and
// outflow, a moving sphere and interpolated bounce-back cover the fp16 variants of lbm_step (interior and
// boundary) and lbm_init; the fp32 result of the same scene is the "feature off" that must differ.
constexpr double kFp16Tolerance = 1e-4;

json fp16(json scene) {
  return withPatch(std::move(scene), {{"fluid", {{"population_storage", "fp16"}}}});
}

TEST_F(LbmStepTest, Fp16StorageInAPeriodicBox) {
  const json scene = latticeScene(kSize, kViscosity);
  expectMatchesCpu(fp16(scene), 5, withPatch(scene, {{"fluid", {{"viscosity", 1.0}}}}), kFp16Tolerance);
}

TEST_F(LbmStepTest, Fp16StorageWithWallsInflowAndOutflow) {
  const json channel = {{"boundaries",
                         {{"x-", "inflow"},
                          {"x+", "outflow"},
                          {"y-", "no_slip"},
                          {"y+", "free_slip"},
                          {"z-", "no_slip"},
                          {"z+", "no_slip"},
                          {"wind", {0.04, 0.0, 0.01}}}}};
  const json scene = latticeScene(kSize, kViscosity, channel);
  expectMatchesCpu(fp16(scene), 5, latticeScene(kSize, kViscosity), kFp16Tolerance);
}

TEST_F(LbmStepTest, Fp16StorageAroundAMovingSphereWithInterpolatedBounceBack) {
  const json moving = {{"obstacles",
                        {{{"type", "sphere"},
                          {"radius", 3.1},
                          {"motion",
                           {{"keyframes",
                             {{{"time", -10.0}, {"position", {6.6, 7.0, 4.65}}},
                              {{"time", 100.0}, {"position", {19.8, -0.7, 10.15}}}}}}}}}}};
  const json scene = interpolated(latticeScene(kSize, kViscosity, moving));
  expectMatchesCpu(fp16(scene), 5, latticeScene(kSize, kViscosity), kFp16Tolerance);
}

TEST_F(LbmStepTest, InterpolatedBounceBackInOneCellGaps) {
  // Links with q < ½ whose next cell away from the wall is not fluid stay half-way: a sphere 0.2 cells above
  // the y− wall (x + c_i lies outside the lattice) and a box and a sphere one cell apart (x + c_i is solid).
  const json gaps = {{"boundaries", {{"y-", "no_slip"}, {"y+", "no_slip"}}},
                     {"obstacles",
                      {{{"type", "sphere"}, {"center", {3.6, 2.9, 5.15}}, {"radius", 2.2}},
                       {{"type", "box"}, {"center", {8.2, 7.0, 5.3}}, {"size", {4.0, 4.3, 3.1}}},
                       {{"type", "sphere"}, {"center", {13.5, 7.2, 5.15}}, {"radius", 2.2}}}}};
  const json halfWay = latticeScene(kSize, kViscosity, gaps);
  expectMatchesCpu(interpolated(halfWay), 5, halfWay);
}

TEST_F(LbmStepTest, InterpolatedBounceBackOnAMovingSphere) {
  // Cells covered and uncovered within the five steps (MovingSphereBounceBackAndRefill): links to a cell
  // uncovered this step stay half-way.
  const json keyframes = {{{"time", -10.0}, {"position", {6.6, 7.04, 4.6}}},
                          {{"time", 100.0}, {"position", {19.8, -0.66, 10.1}}}};
  const json moving = {
      {"obstacles", {{{"type", "sphere"}, {"radius", 3.1}, {"motion", {{"keyframes", keyframes}}}}}}};
  const json halfWay = latticeScene(kSize, kViscosity, moving);
  expectMatchesCpu(interpolated(halfWay), 5, halfWay);
}

TEST_F(LbmStepTest, VelocityInletDisk) {
  const json inlet = {{"inlets",
                       {{{"shape", "disk"},
                         {"center", {8.0, 2.2, 5.4}},
                         {"radius", 2.3},
                         {"normal", {0.0, 1.0, 0.0}},
                         {"velocity", 0.07},
                         {"noise", 0.0},
                         {"density", 1.5},
                         {"temperature", 0.5}}}}};
  expectMatchesCpu(latticeScene(kSize, kViscosity, inlet), 5, latticeScene(kSize, kViscosity));
}

TEST_F(LbmStepTest, BuoyancyFromSmoke) {
  const json buoyant = {
      {"fluid", {{"buoyancy", {{"temperature", 2e-3}, {"density", -1e-3}}}, {"gravity", {0.3, -1.0, 0.2}}}}};
  expectMatchesCpu(latticeScene(kSize, kViscosity, buoyant), 5, latticeScene(kSize, kViscosity));
}

TEST_F(LbmStepTest, BuoyancyFromAFinerSmokeGrid) {
  // The force averages the 2³ smoke cells of each lattice cell. Closed walls keep this test apart from
  // the transport across periodic faces (SmokeTransportTest.FinerSmokeGridPeriodic).
  const json closed = {{"grid", {{"smoke_upres", 2}}},
                       {"boundaries",
                        {{"x-", "no_slip"},
                         {"x+", "no_slip"},
                         {"y-", "no_slip"},
                         {"y+", "no_slip"},
                         {"z-", "no_slip"},
                         {"z+", "no_slip"}}}};
  const json scene = latticeScene(kSize, kViscosity, closed);
  expectMatchesCpu(withPatch(scene, {{"fluid", {{"buoyancy", {{"temperature", 2e-3}, {"density", -1e-3}}}}}}),
                   3, scene);
}

TEST_F(LbmStepTest, SmagorinskyEddyViscosity) {
  const json scene = latticeScene(kSize, 0.002, {{"fluid", {{"smagorinsky", 0.15}}}});
  expectMatchesCpu(scene, 5, withPatch(scene, {{"fluid", {{"smagorinsky", 0.0}}}}));
}

// Guo forcing adds exactly F = ρa of momentum per step (Σ c_i f_i* = Σ c_i f_i + F), and the reported
// velocity carries the half-force shift: from rest, every cell has u = (n − ½) a after n steps. Exact
// physics, independent of the oracle; float rounding stays below 1e-8 here.
TEST_F(LbmStepTest, UniformBodyForceAddsExactlyFPerStep) {
  const glm::dvec3 a(4e-4, -2e-4, 1e-4);
  const int steps = 5;
  sim::Simulation gpu(
      context(), pipelineCache(),
      parseLatticeScene(latticeScene(kSize, kViscosity, {{"fluid", {{"body_force", {a.x, a.y, a.z}}}}})));
  gpu.advance(steps);
  double worst = 0;
  for (const glm::vec4& m : gpu.lbm().macro().download<glm::vec4>())
    worst = std::max(worst, glm::length(glm::dvec3(m) - (steps - 0.5) * a));
  EXPECT_LE(worst, 1e-6) << "expected u = " << (steps - 0.5) * a.x << ", " << (steps - 0.5) * a.y << ", "
                         << (steps - 0.5) * a.z;
  std::cout << "[ measured ] max |u − (n − ½) a| " << worst << "\n";
}

TEST_F(LbmStepTest, BodyForce) {
  const json pushed = {{"fluid", {{"body_force", {4e-4, -2e-4, 1e-4}}}}};
  expectMatchesCpu(latticeScene(kSize, kViscosity, pushed), 5, latticeScene(kSize, kViscosity));
}

// A sphere dragged by sim::Simulation::steerObstacle (the demo) moves like a scene whose keyframes are the
// steered motion: the CPU reference runs that scene.
TEST_F(LbmStepTest, SteeredSphereMatchesItsKeyframedMotion) {
  const glm::vec3 start(5.91f, 5.48f, 5.2f), target(9.6f, 6.4f, 5.2f);
  const auto sphere = [&](const json& motion) {
    json s = {{"type", "sphere"}, {"radius", 2.4}};
    if (motion.is_null())
      s["center"] = {start.x, start.y, start.z};
    else
      s["motion"] = motion;
    return latticeScene(kSize, kViscosity, {{"obstacles", {s}}});
  };
  const scene::Scene still = parseLatticeScene(sphere(nullptr));
  const Initial init = initialState(still);
  sim::Simulation gpu(context(), pipelineCache(), still);
  gpu.setFlow(init.velocity, init.density);
  gpu.smoke().upload(init.smoke);
  gpu.advance(2);
  gpu.steerObstacle(0, target);
  const scene::Motion& steered = *gpu.obstacleMotion(0);
  ASSERT_EQ(steered.keyframes.size(), 2u);
  EXPECT_EQ(steered.keyframes[0].time, 2.0f);
  EXPECT_EQ(steered.keyframes[0].position, start);
  EXPECT_EQ(steered.keyframes[1].position, target);
  // Half the lattice speed limit (0.1 cells per step by default) at most.
  const float speed = glm::length(target - start) / (steered.keyframes[1].time - steered.keyframes[0].time);
  EXPECT_LE(speed, 0.05f + 1e-6f);
  EXPECT_GE(speed, 0.049f);
  const int steps = 12;
  gpu.advance(steps - 2);

  json keyframes = json::array();
  for (const scene::Keyframe& k : steered.keyframes)
    keyframes.push_back({{"time", k.time}, {"position", {k.position.x, k.position.y, k.position.z}}});
  const scene::Scene keyframed = parseLatticeScene(sphere({{"keyframes", keyframes}}));
  const CpuSimulation probe(keyframed);
  for (int s = 0; s <= steps; ++s) ASSERT_GT(probe.surfaceMargin(s), kSurfaceMargin) << "step " << s;
  const std::vector<glm::vec4> gpuMacro = gpu.lbm().macro().download<glm::vec4>();
  const std::vector<glm::dvec4> expected = cpuMacro(keyframed, steps);
  const FieldError u = velocityError(gpuMacro, expected), rho = densityError(gpuMacro, expected);
  EXPECT_LE(u.max, kTolerance) << "velocity" << describe(u, keyframed, gpuMacro, expected);
  EXPECT_LE(rho.max, kTolerance) << "density" << describe(rho, keyframed, gpuMacro, expected);
  const FieldError effect = maxDifference(expected, cpuMacro(still, steps));
  EXPECT_GT(effect.max, 10 * kTolerance) << "the drag hardly changes the flow";
  std::cout << "[ measured ] max |Δu| " << u.max << ", max |Δρ| " << rho.max << "; drag effect " << effect.max
            << "\n";
}

// The demo's inlet strength s runs the scene as if its inlets blew at s times their velocity.
TEST_F(LbmStepTest, InletStrengthScalesTheInletVelocity) {
  const auto withInlet = [](double velocity) {
    return latticeScene(kSize, kViscosity,
                        {{"inlets",
                          {{{"shape", "disk"},
                            {"center", {8.0, 2.2, 5.4}},
                            {"radius", 2.3},
                            {"normal", {0.0, 1.0, 0.0}},
                            {"velocity", velocity},
                            {"noise", 0.0},
                            {"density", 1.5},
                            {"temperature", 0.5}}}}});
  };
  const scene::Scene scene = parseLatticeScene(withInlet(0.07));
  const Initial init = initialState(scene);
  sim::Simulation gpu(context(), pipelineCache(), scene);
  // The fastest inlet may go up to the lattice speed limit: 0.1 / 0.07.
  EXPECT_NEAR(gpu.maxInletStrength(), 0.1f / 0.07f, 1e-5f);
  EXPECT_THROW(gpu.setInletStrength(1.5f), std::invalid_argument);
  EXPECT_THROW(gpu.setInletStrength(-0.1f), std::invalid_argument);
  gpu.setInletStrength(0.5f);
  gpu.setFlow(init.velocity, init.density);
  gpu.smoke().upload(init.smoke);
  gpu.advance(5);
  const std::vector<glm::vec4> gpuMacro = gpu.lbm().macro().download<glm::vec4>();
  const scene::Scene halved = parseLatticeScene(withInlet(0.035));
  const std::vector<glm::dvec4> expected = cpuMacro(halved, 5);
  const FieldError u = velocityError(gpuMacro, expected);
  EXPECT_LE(u.max, kTolerance) << "velocity" << describe(u, halved, gpuMacro, expected);
  const FieldError effect = maxDifference(expected, cpuMacro(scene, 5));
  EXPECT_GT(effect.max, 10 * kTolerance);
}

}  // namespace
}  // namespace sixway::test
