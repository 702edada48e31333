// Schäfer & Turek (1996), "flow around a cylinder", case 2D-1 as a quasi-2D run (one periodic cell
// deep): channel 2.2 × 0.41 m, cylinder of diameter D = 0.1 m centred at (0.2, 0.2), parabolic inflow
// of peak 0.3 m/s (mean Ū = 0.2), ν = 1e-3 m²/s, Re = Ū D / ν = 20. Published drag coefficient
// c_D = 2 F_x / (ρ Ū² D) ∈ [5.57, 5.59]. docs/validation.md shows the grid convergence. Run with both
// obstacle boundary rules (fluid.obstacle_boundary): half-way and interpolated (Bouzidi) bounce-back.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "sim/simulation.h"
#include "support/gpu_fixture.h"

namespace sixway::test {
namespace {

// Drag coefficient at `cellsPerDiameter`, averaged over the last 500 steps of a run of
// `flowThroughs` channel lengths (at the mean speed). The channel starts filled with the inflow's
// Poiseuille profile: from rest, a slowly damped acoustic mode between inlet and outlet (1/e in
// ~10⁵ steps at this viscosity) would sway the drag for many flow-throughs.
// `maxLatticeVelocity`: the inflow's peak in cells/step (its Mach number / √3).
double dragCoefficient(const gpu::Context& context, const gpu::PipelineCache& cache, int cellsPerDiameter,
                       double flowThroughs, const std::string& obstacleBoundary = "half_way",
                       double maxLatticeVelocity = 0.1) {
  const double dx = 0.1 / cellsPerDiameter;
  const nlohmann::json j = {
      {"grid", {{"size", {22 * cellsPerDiameter, int(std::lround(0.41 / dx)), 1}}, {"cell_size", dx}}},
      {"time", {{"frame_dt", 0.1}}},
      {"fluid",
       {{"viscosity", 1e-3},
        {"smagorinsky", 0.0},
        {"max_lattice_velocity", maxLatticeVelocity},
        {"obstacle_boundary", obstacleBoundary}}},
      {"boundaries",
       {{"x-", "inflow"},
        {"x+", "outflow"},
        {"y-", "no_slip"},
        {"y+", "no_slip"},
        {"z-", "periodic"},
        {"z+", "periodic"},
        {"wind", {0.3, 0.0, 0.0}},
        {"inflow_profile", "parabolic"}}},
      {"obstacles",
       {{{"type", "cylinder"},
         {"center", {0.2, 0.2, 0.5 * dx}},
         {"radius", 0.05},
         {"height", 1.0},
         {"axis", {0.0, 0.0, 1.0}}}}},
      {"camera", {{"position", {1, 0.2, 3}}, {"target", {1, 0.2, 0}}}},
  };
  const io::Scene scene = io::parseScene(j, "schaefer-turek-2d1", ".");
  sim::Simulation simulation(context, cache, scene);
  std::vector<glm::vec3> velocity;
  for (int y = 0; y < scene.grid.size.y; ++y) {
    const double s = (y + 0.5) / scene.grid.size.y;
    for (int x = 0; x < scene.grid.size.x; ++x) velocity.emplace_back(0.3 * 4 * s * (1 - s), 0.0, 0.0);
  }
  simulation.setFlow(velocity, std::vector<float>(velocity.size(), 1.0f));
  const sim::LatticeUnits& u = simulation.units();
  const double meanSpeed = u.toLatticeVelocity(0.2f);  // cells/step
  const auto steps = uint32_t(flowThroughs * 22 * cellsPerDiameter / meanSpeed);
  simulation.advance(steps - 500);
  double drag = 0;
  for (int i = 0; i < 500; i += 50) {
    simulation.advance(50);
    for (const auto& step : simulation.report().forces) drag += step[0].x;
  }
  drag /= 500;
  return 2 * drag / (meanSpeed * meanSpeed * cellsPerDiameter);  // one cell deep
}

TEST_F(GpuTest, SchaeferTurek2D1DragAtTenCellsPerDiameter) {
  const double cd = dragCoefficient(context(), pipelineCache(), 10, 2);
  RecordProperty("drag_coefficient", std::to_string(cd));
  // 10 cells per diameter: half-way bounce-back on a staircase circle acts like a slightly larger
  // cylinder (first-order boundary error), so c_D reads high here and falls toward the published
  // interval as the grid is refined (LONG_ test and docs/validation.md). Allowed: 10% above.
  EXPECT_GT(cd, 5.57) << "c_D at D = 10 cells";
  EXPECT_LT(cd, 1.10 * 5.59) << "c_D at D = 10 cells";
}

// Interpolated (Bouzidi) bounce-back puts the wall where each link crosses the circle, which removes the
// staircase's first-order excess: c_D must come out below half-way bounce-back's 6.067 on the same grid
// (measured 5.93, docs/validation.md). What remains above the published interval is mostly the
// compressibility of the lattice at this Mach number (0.17 at the inflow's peak), which refining the grid
// at a fixed lattice velocity does not remove (LONG_ tests below).
TEST_F(GpuTest, SchaeferTurek2D1InterpolatedDragAtTenCellsPerDiameter) {
  const double cd = dragCoefficient(context(), pipelineCache(), 10, 2, "interpolated");
  RecordProperty("drag_coefficient", std::to_string(cd));
  std::printf("interpolated, D = 10 cells: c_D = %.4f\n", cd);
  EXPECT_GT(cd, 5.57) << "c_D at D = 10 cells";
  EXPECT_LT(cd, 5.99) << "c_D at D = 10 cells (half-way bounce-back: 6.067)";
}

// Ten minutes on lavapipe (CTest label "long"): D = 20 cells, below half-way bounce-back's 5.882 there.
TEST_F(GpuTest, LONG_SchaeferTurek2D1InterpolatedDragAtTwentyCellsPerDiameter) {
  const double cd = dragCoefficient(context(), pipelineCache(), 20, 2, "interpolated");
  RecordProperty("drag_coefficient", std::to_string(cd));
  std::printf("interpolated, D = 20 cells: c_D = %.4f\n", cd);
  EXPECT_GT(cd, 5.57) << "c_D at D = 20 cells";
  EXPECT_LT(cd, 5.85) << "c_D at D = 20 cells (half-way bounce-back: 5.882)";
}

// The same at half the lattice velocity (Mach 0.087, twice the steps): a compressibility error, ∝ Ma²,
// falls to a quarter and c_D moves toward the published interval.
TEST_F(GpuTest, LONG_SchaeferTurek2D1InterpolatedDragAtTwentyCellsPerDiameterAndHalfTheMach) {
  const double cd = dragCoefficient(context(), pipelineCache(), 20, 2, "interpolated", 0.05);
  RecordProperty("drag_coefficient", std::to_string(cd));
  std::printf("interpolated, D = 20 cells, lattice velocity 0.05: c_D = %.4f\n", cd);
  EXPECT_GT(cd, 5.57) << "c_D at D = 20 cells, Mach 0.087";
  EXPECT_LT(cd, 5.72) << "c_D at D = 20 cells, Mach 0.087";
}

// The grid-convergence runs (minutes each on lavapipe); CTest label "long". The error against the
// published value must shrink with every refinement.
TEST_F(GpuTest, LONG_SchaeferTurek2D1DragConvergence) {
  double previousError = 1e9;
  for (int cells : {10, 20, 40}) {
    const double cd = dragCoefficient(context(), pipelineCache(), cells, 2);
    RecordProperty("drag_coefficient_" + std::to_string(cells), std::to_string(cd));
    std::printf("D = %d cells: c_D = %.4f\n", cells, cd);
    std::fflush(stdout);
    const double error = std::fabs(cd - 5.58);
    EXPECT_LT(error, previousError) << "no convergence at D = " << cells;
    previousError = error;
  }
}

}  // namespace
}  // namespace sixway::test
