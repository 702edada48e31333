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

struct Drag {
  double coefficient;    // 2 F_x / (ρ∞ Ū² D), ρ∞ the density of the inflow (the free stream)
  double atRestDensity;  // 2 F_x / (ρ₀ Ū² D) with the lattice's rest density ρ₀ = 1
  double inflowDensity;  // ρ∞
};

// Drag at `cellsPerDiameter` after `flowThroughs` channel lengths (at the mean speed). The channel starts
// filled with the inflow's Poiseuille profile: from rest, a slowly damped acoustic mode between inlet and
// outlet (1/e in ~10⁵ steps at this viscosity) would sway the drag for many flow-throughs. What is left of
// that mode is a quarter-wave between the inflow (a velocity wall, closed) and the outflow (fixed pressure,
// open) of period 4 L / c_s steps, L the channel length in cells and c_s = 1/√3; the drag swings ±0.5% with
// it, so it is averaged over the last two periods. In this weakly compressible fluid the pressure that drives
// the flow down the channel and past the cylinder raises the density at the inflow above ρ₀ (by 2.3% at
// D = 10 cells and Mach 0.17, ∝ Ma²); the velocity inflow then carries ρ∞ Ū of momentum per unit area, and
// c_D is taken, as its definition says, with the free stream's density.
// `maxLatticeVelocity`: the inflow's peak in cells/step (its Mach number / √3).
Drag drag(const gpu::Context& context, const gpu::PipelineCache& cache, int cellsPerDiameter,
          double flowThroughs, const std::string& obstacleBoundary = "half_way",
          double maxLatticeVelocity = 0.1, const std::string& populationStorage = "fp32") {
  const double dx = 0.1 / cellsPerDiameter;
  const nlohmann::json j = {
      {"grid", {{"size", {22 * cellsPerDiameter, int(std::lround(0.41 / dx)), 1}}, {"cell_size", dx}}},
      {"time", {{"frame_dt", 0.1}}},
      {"fluid",
       {{"viscosity", 1e-3},
        {"smagorinsky", 0.0},
        {"max_lattice_velocity", maxLatticeVelocity},
        {"obstacle_boundary", obstacleBoundary},
        {"population_storage", populationStorage}}},
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
  const scene::Scene scene = scene::parseScene(j, "schaefer-turek-2d1", ".");
  const int nx = scene.grid.size.x, ny = scene.grid.size.y;
  sim::Simulation simulation(context, cache, scene);
  std::vector<glm::vec3> velocity;
  for (int y = 0; y < ny; ++y) {
    const double s = (y + 0.5) / ny;
    for (int x = 0; x < nx; ++x) velocity.emplace_back(0.3 * 4 * s * (1 - s), 0.0, 0.0);
  }
  simulation.setFlow(velocity, std::vector<float>(velocity.size(), 1.0f));
  const double meanSpeed = simulation.units().toLatticeVelocity(0.2f);  // cells/step
  constexpr uint32_t kChunk = 50;
  const auto steps = uint32_t(flowThroughs * nx / meanSpeed) / kChunk * kChunk;
  const auto window = uint32_t(2 * 4 * nx * std::sqrt(3.0)) / kChunk * kChunk;
  simulation.advance(steps - window);
  double force = 0, inflowDensity = 0;
  for (uint32_t i = 0; i < window; i += kChunk) {
    simulation.advance(kChunk);
    for (const auto& step : simulation.report().forces) force += step[0].x;
    const std::vector<glm::vec4> macro = simulation.lbm().macro().download<glm::vec4>();
    for (int y = 0; y < ny; ++y) inflowDensity += macro[size_t(y) * nx].w;
  }
  force /= window;
  inflowDensity /= double(window / kChunk) * ny;
  const double nominal = 2 * force / (meanSpeed * meanSpeed * cellsPerDiameter);  // one cell deep
  return {nominal / inflowDensity, nominal, inflowDensity};
}

void record(const Drag& d, const char* what) {
  ::testing::Test::RecordProperty("drag_coefficient", std::to_string(d.coefficient));
  ::testing::Test::RecordProperty("drag_coefficient_rest_density", std::to_string(d.atRestDensity));
  ::testing::Test::RecordProperty("inflow_density", std::to_string(d.inflowDensity));
  std::printf("%s: c_D = %.4f (with rho0 = 1: %.4f; inflow density %.5f)\n", what, d.coefficient,
              d.atRestDensity, d.inflowDensity);
  std::fflush(stdout);
}

TEST_F(GpuTest, SchaeferTurek2D1DragAtTenCellsPerDiameter) {
  const Drag d = drag(context(), pipelineCache(), 10, 2);
  record(d, "half-way, D = 10 cells");
  // 10 cells per diameter: half-way bounce-back on a staircase circle acts like a slightly larger
  // cylinder (first-order boundary error), so c_D reads high here and falls toward the published
  // interval as the grid is refined (LONG_ test and docs/validation.md). Allowed: 10% above.
  EXPECT_GT(d.coefficient, 5.57) << "c_D at D = 10 cells";
  EXPECT_LT(d.coefficient, 1.10 * 5.59) << "c_D at D = 10 cells";
}

// Interpolated (Bouzidi) bounce-back puts the wall where each link crosses the circle, which removes the
// staircase's first-order excess: measured 5.82 against half-way bounce-back's 5.96 on the same grid
// (docs/validation.md). Allowed: 5% above the published interval.
TEST_F(GpuTest, SchaeferTurek2D1InterpolatedDragAtTenCellsPerDiameter) {
  const Drag d = drag(context(), pipelineCache(), 10, 2, "interpolated");
  record(d, "interpolated, D = 10 cells");
  EXPECT_GT(d.coefficient, 5.57) << "c_D at D = 10 cells";
  EXPECT_LT(d.coefficient, 1.05 * 5.59) << "c_D at D = 10 cells";
}

// The same with 16-bit population storage (lbm_lattice.glsl): the same bounds.
TEST_F(GpuTest, SchaeferTurek2D1InterpolatedDragAtTenCellsPerDiameterWithFp16Populations) {
  const Drag d = drag(context(), pipelineCache(), 10, 2, "interpolated", 0.1, "fp16");
  record(d, "interpolated, fp16 populations, D = 10 cells");
  EXPECT_GT(d.coefficient, 5.57) << "c_D at D = 10 cells";
  EXPECT_LT(d.coefficient, 1.05 * 5.59) << "c_D at D = 10 cells";
}

// Ten minutes on lavapipe (CTest label "long"): D = 20 cells at the same lattice velocity as D = 10, so
// the same Mach number (0.17); the grid's share of the error falls, the compressibility's does not.
TEST_F(GpuTest, LONG_SchaeferTurek2D1InterpolatedDragAtTwentyCellsPerDiameter) {
  const Drag d = drag(context(), pipelineCache(), 20, 2, "interpolated");
  record(d, "interpolated, D = 20 cells");
  EXPECT_GT(d.coefficient, 5.57) << "c_D at D = 20 cells";
  EXPECT_LT(d.coefficient, 1.03 * 5.59) << "c_D at D = 20 cells";
}

// Diffusive scaling (12 minutes on lavapipe, label "long"): D = 20 cells at half the lattice velocity
// of the D = 10 run. Re and τ (0.6) stay the same and the Mach number halves with the cell size, so every
// error of the scheme, compressibility included, is O(Δx²): c_D must approach the published interval, and
// Richardson extrapolation, c∞ = c₂₀ + (c₂₀ − c₁₀)/3, estimates the converged value (docs/validation.md).
TEST_F(GpuTest, LONG_SchaeferTurek2D1InterpolatedDragDiffusiveScaling) {
  const Drag coarse = drag(context(), pipelineCache(), 10, 2, "interpolated", 0.1);
  record(coarse, "interpolated, D = 10 cells, lattice velocity 0.1");
  const Drag fine = drag(context(), pipelineCache(), 20, 2, "interpolated", 0.05);
  record(fine, "interpolated, D = 20 cells, lattice velocity 0.05");
  const double extrapolated = fine.coefficient + (fine.coefficient - coarse.coefficient) / 3;
  RecordProperty("drag_coefficient_extrapolated", std::to_string(extrapolated));
  std::printf("Richardson extrapolation (second order): c_D = %.4f\n", extrapolated);
  EXPECT_LT(std::fabs(fine.coefficient - 5.58), std::fabs(coarse.coefficient - 5.58));
  EXPECT_LT(std::fabs(extrapolated - 5.58), 0.01 * 5.58) << "extrapolated c_D";
}

// The third grid of the diffusive series (label "long"): D = 40 cells at 0.025 cells/step (τ = 0.6 again,
// Mach 0.043), 16 times the D = 20 run's work: 105,600 steps at 38–53 ms on lavapipe, 1–1.5 hours; not run to
// the end yet (docs/validation.md). From the two coarser grids, second-order convergence predicts 5.607;
// allowed: within 0.5% of the published interval.
TEST_F(GpuTest, LONG_SchaeferTurek2D1InterpolatedDragAtFortyCellsPerDiameter) {
  const Drag d = drag(context(), pipelineCache(), 40, 2, "interpolated", 0.025);
  record(d, "interpolated, D = 40 cells, lattice velocity 0.025");
  EXPECT_GT(d.coefficient, 0.995 * 5.57) << "c_D at D = 40 cells";
  EXPECT_LT(d.coefficient, 1.005 * 5.59) << "c_D at D = 40 cells";
}

// The grid-convergence runs (minutes each on lavapipe); CTest label "long". The error against the
// published value must shrink with every refinement.
TEST_F(GpuTest, LONG_SchaeferTurek2D1DragConvergence) {
  double previousError = 1e9;
  for (int cells : {10, 20, 40}) {
    const double cd = drag(context(), pipelineCache(), cells, 2).coefficient;
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
