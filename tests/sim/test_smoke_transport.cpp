// shaders/sim/smoke_sources.comp and fct_*.comp (through sim::SmokeTransport, with flags and velocity
// buffers made here) against the CPU FCT oracle (cpu_fct.h), a few steps from random smoke.
//
// Tolerance: max |GPU − CPU| ≤ 1e-5 × the range of the initial values, per component. Each substep is
// a few float operations per value (ε = 6e-8), and the limiter only scales fluxes by factors in [0, 1],
// so after a few substeps the expected difference is ~1e-6 of the range; a wrong flux, face velocity
// or limiter choice moves values by a fraction of the range. Conservation (closed box): |Σ after −
// Σ before| ≤ cells · ε · max|q|, the worst case of one rounding per cell. Positivity: no value below
// −ε · max|q| (FCT keeps every value within the bounds of its neighbourhood, here ≥ 0).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <numbers>
#include <random>

#include "cpu_fct.h"
#include "gpu/buffer.h"
#include "gpu/sequence.h"
#include "gpu_state.h"
#include "scene_fixtures.h"
#include "sim/sim_params.h"
#include "sim/smoke_transport.h"
#include "support/gpu_fixture.h"

namespace sixway::test {
namespace {

using scene::BoundaryType;
using Faces = std::array<BoundaryType, 6>;

constexpr glm::ivec3 kLattice{12, 10, 8};
constexpr double kTolerance = 1e-5;  // relative to the data range
constexpr double kEpsilon = 6e-8;    // float rounding

constexpr Faces kPeriodic = {BoundaryType::Periodic, BoundaryType::Periodic, BoundaryType::Periodic,
                             BoundaryType::Periodic, BoundaryType::Periodic, BoundaryType::Periodic};
constexpr Faces kClosed = {BoundaryType::NoSlip, BoundaryType::FreeSlip, BoundaryType::NoSlip,
                           BoundaryType::NoSlip, BoundaryType::FreeSlip, BoundaryType::NoSlip};
constexpr Faces kOpen = {BoundaryType::Inflow,  BoundaryType::Outflow,  BoundaryType::NoSlip,
                         BoundaryType::Outflow, BoundaryType::Periodic, BoundaryType::Periodic};

size_t cellCount(glm::ivec3 n) {
  return size_t(n.x) * n.y * n.z;
}

std::vector<glm::vec2> randomSmoke(glm::ivec3 n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> density(0.0f, 2.0f), temperature(0.0f, 1.0f);
  std::vector<glm::vec2> out(cellCount(n));
  for (glm::vec2& v : out) v = {density(rng), temperature(rng)};
  return out;
}

// u = (A sin(2π y/ny + φ), B sin(2π z/nz + φ), C sin(2π x/nx + φ)): no component varies along its own
// axis, so the face fluxes of every cell cancel for a uniform q (discretely divergence-free).
std::vector<glm::vec3> divergenceFreeVelocity(glm::ivec3 n) {
  std::vector<glm::vec3> out(cellCount(n));
  for (size_t c = 0; c < out.size(); ++c) {
    const glm::dvec3 x = 2 * std::numbers::pi * (glm::dvec3(cellOf(int(c), n)) + 0.5) / glm::dvec3(n);
    out[c] = glm::vec3(0.25 * std::sin(x.y + 0.3), -0.2 * std::sin(x.z + 1.1), 0.22 * std::sin(x.x + 2.0));
  }
  return out;
}

std::vector<glm::vec3> divergentVelocity(glm::ivec3 n) {
  return smoothVelocity(n, 0.25f, 11);
}

struct SmokeCase {
  Faces faces = kPeriodic;
  int upres = 1;
  std::vector<glm::vec3> velocity;  // per lattice cell, cells per step
  std::vector<bool> solid;          // per lattice cell; empty: none
  glm::ivec3 lattice = kLattice;
  bool sparse = true;  // sim::SmokeSettings
  float sparseThreshold = 1e-6f;
};

class SmokeTransportTest : public GpuTest {
 protected:
  // `steps` lattice steps of transport on the GPU.
  std::vector<glm::vec2> gpuTransport(const SmokeCase& c, const std::vector<glm::vec2>& smoke, int steps) {
    sim::SmokeSettings settings;
    settings.lattice = c.lattice;
    settings.upres = c.upres;
    settings.faces = c.faces;
    settings.sparse = c.sparse;
    settings.sparseThreshold = c.sparseThreshold;
    sim::SmokeTransport transport(context(), pipelineCache(), settings);
    transport.upload(smoke);
    gpu::Buffer flags = gpu::Buffer::storage(context(), cellCount(c.lattice) * 4, "flags");
    std::vector<uint32_t> flagWords(cellCount(c.lattice), 0u);
    for (size_t i = 0; i < c.solid.size(); ++i) flagWords[i] = c.solid[i] ? 1u : 0u;  // obstacle 0
    flags.upload(flagWords);
    gpu::Buffer macro = gpu::Buffer::storage(context(), cellCount(c.lattice) * 16, "velocity");
    std::vector<glm::vec4> macroValues;
    for (const glm::vec3& u : c.velocity) macroValues.emplace_back(u, 1.0f);
    macro.upload(macroValues);
    gpu::Sequence sequence(context(), transport.stagesPerStep() * uint32_t(steps));
    for (int s = 0; s < steps; ++s) transport.recordTransport(sequence, flags, macro);
    sequence.submit();
    activeBricks_ = transport.activeBricks();
    bricks_ = transport.bricks();
    return transport.download();
  }

  std::vector<glm::dvec2> cpuTransport(const SmokeCase& c, const std::vector<glm::vec2>& smoke, int steps) {
    const CpuSmokeSettings settings{c.lattice, c.upres, c.faces};
    const std::vector<bool> solid =
        c.solid.empty() ? std::vector<bool>(cellCount(c.lattice), false) : c.solid;
    std::vector<glm::dvec2> out = toDouble(smoke);
    for (int s = 0; s < steps; ++s) transportSmoke(settings, solid, toDouble(c.velocity), out);
    return out;
  }

  // Compares GPU and CPU after `steps`; returns the GPU result for further checks.
  std::vector<glm::vec2> expectMatchesCpu(const SmokeCase& c, int steps) {
    return expectMatchesCpu(c, randomSmoke(c.lattice * c.upres, 5), glm::dvec2(2.0, 1.0), steps);
  }

  // The same from `initial`, whose values span `range` per component; `tolerance` relative to that.
  std::vector<glm::vec2> expectMatchesCpu(const SmokeCase& c, const std::vector<glm::vec2>& initial,
                                          glm::dvec2 range, int steps, double tolerance = kTolerance) {
    const glm::ivec3 n = c.lattice * c.upres;
    const std::vector<glm::vec2> got = gpuTransport(c, initial, steps);
    const std::vector<glm::dvec2> expected = cpuTransport(c, initial, steps);
    for (int component = 0; component < 2; ++component) {
      double worst = 0, moved = 0;
      int where = 0;
      for (size_t i = 0; i < got.size(); ++i) {
        moved = std::max(moved, std::abs(expected[i][component] - initial[i][component]));
        const double error = std::abs(got[i][component] - expected[i][component]);
        if (!(error <= worst)) {
          worst = error;
          where = int(i);
        }
      }
      EXPECT_LE(worst, tolerance * range[component])
          << "component " << component << " differs most at smoke " << FieldError{0, where}.where(n)
          << ": GPU " << got[where][component] << ", CPU " << expected[where][component];
      EXPECT_GT(moved, 100 * tolerance * range[component]) << "the smoke hardly moved";
      std::cout << "[ measured ] component " << component << ": max |Δ| / range " << worst / range[component]
                << " (largest change " << moved / range[component] << " of the range)\n";
    }
    return got;
  }

  // SourcesSetInletCellsAndDecayTheRest with the sparse or the dense transport.
  void expectSourcesMatchCpu(bool sparse);

  uint64_t activeBricks_ = 0, bricks_ = 0;  // of the last gpuTransport()
};

// The sparse transport's cases: a lattice of 6×5×4 bricks at upres 1, so that most of it is far from the
// smoke.
constexpr glm::ivec3 kSparseLattice{24, 20, 16};

// Two blobs of smoke in clean air, one of them across the x seam (periodic in the periodic cases), each
// (1.5, 0.8) · (1 − r²/R²) inside its radius R of 3 lattice cells and exactly 0 outside; plus, where `faint`
// > 0, a brick-aligned 8×4×4-lattice-cell patch of that value far from both.
std::vector<glm::vec2> blobSmoke(glm::ivec3 lattice, int upres, float faint) {
  const glm::ivec3 n = lattice * upres;
  std::vector<glm::vec2> out(cellCount(n), glm::vec2(0));
  for (int i = 0; i < int(out.size()); ++i) {
    const glm::vec3 p = (glm::vec3(cellOf(i, n)) + 0.5f) / float(upres);  // lattice units
    for (const glm::vec3 centre : {glm::vec3(7, 6, 5), glm::vec3(0.5f, 14, 11)}) {
      glm::vec3 d = p - centre;
      d.x -= float(lattice.x) * std::round(d.x / float(lattice.x));  // the nearer image across the seam
      const float r2 = glm::dot(d, d) / 9.0f;
      if (r2 < 1) out[i] += glm::vec2(1.5f, 0.8f) * (1 - r2);
    }
    if (faint > 0 && p.x >= 12 && p.x < 20 && p.y >= 0 && p.y < 4 && p.z >= 8 && p.z < 12)
      out[i] = glm::vec2(faint);
  }
  return out;
}

// With a threshold of 0 the sparse transport skips only bricks whose values and neighbours' are all 0, whose
// new values are then 0 too: it must give the dense transport's values exactly (and both the CPU oracle's).
TEST_F(SmokeTransportTest, SparseTransportEqualsTheDenseOne) {
  for (const auto& [faces, upres] : {std::pair{kPeriodic, 1}, std::pair{kOpen, 2}}) {
    SCOPED_TRACE("upres " + std::to_string(upres));
    const std::vector<glm::vec2> initial = blobSmoke(kSparseLattice, upres, 0);
    SmokeCase dense{faces, upres, divergentVelocity(kSparseLattice), {}, kSparseLattice, false, 0};
    const std::vector<glm::vec2> expected = expectMatchesCpu(dense, initial, glm::dvec2(1.5, 0.8), 3);
    EXPECT_EQ(activeBricks_, bricks_) << "the dense transport computes every brick";
    SmokeCase sparse = dense;
    sparse.sparse = true;
    const std::vector<glm::vec2> got = expectMatchesCpu(sparse, initial, glm::dvec2(1.5, 0.8), 3);
    EXPECT_LT(activeBricks_, bricks_ * 3 / 4) << "the sparse transport skipped too little to be tested";
    size_t different = 0;
    for (size_t i = 0; i < got.size(); ++i) different += got[i] != expected[i];
    EXPECT_EQ(different, 0u) << "values of the sparse transport that differ from the dense one's";
    std::cout << "[ measured ] upres " << upres << ": " << activeBricks_ << " of " << bricks_
              << " bricks active in the last substep\n";
  }
}

// With a threshold the smoke at or below it in bricks far from the rest is dropped: the faint patch (half the
// threshold) is gone, and no value differs from the dense CPU oracle's by more than the threshold.
TEST_F(SmokeTransportTest, SparseThresholdDropsOnlyFaintSmokeFarFromTheRest) {
  constexpr float kThreshold = 1e-3f;
  const std::vector<glm::vec2> initial = blobSmoke(kSparseLattice, 1, 0.5f * kThreshold);
  SmokeCase c{kPeriodic, 1, divergentVelocity(kSparseLattice), {}, kSparseLattice, true, kThreshold};
  const std::vector<glm::vec2> got =
      expectMatchesCpu(c, initial, glm::dvec2(1.5, 0.8), 3, kThreshold / 0.8);  // ≤ the threshold
  size_t faintLeft = 0, faintBefore = 0;
  for (size_t i = 0; i < got.size(); ++i) {
    if (initial[i].x != 0.5f * kThreshold) continue;
    ++faintBefore;
    faintLeft += got[i] != glm::vec2(0);
  }
  EXPECT_EQ(faintBefore, 8u * 4u * 4u);
  EXPECT_EQ(faintLeft, 0u) << "cells of the faint patch with smoke left";
}

TEST_F(SmokeTransportTest, PeriodicDivergenceFreeFlow) {
  expectMatchesCpu({kPeriodic, 1, divergenceFreeVelocity(kLattice), {}}, 4);
}

TEST_F(SmokeTransportTest, PeriodicDivergentFlow) {
  expectMatchesCpu({kPeriodic, 1, divergentVelocity(kLattice), {}}, 4);
}

TEST_F(SmokeTransportTest, InflowOutflowAndWallFaces) {
  expectMatchesCpu({kOpen, 1, divergentVelocity(kLattice), {}}, 4);
}

TEST_F(SmokeTransportTest, ObstaclesPassNoSmoke) {
  SmokeCase c{kOpen, 1, divergentVelocity(kLattice), std::vector<bool>(cellCount(kLattice), false)};
  for (int i = 0; i < int(c.solid.size()); ++i) {
    const glm::ivec3 p = cellOf(i, kLattice);
    if (p.x >= 4 && p.x < 7 && p.y >= 3 && p.y < 8 && p.z >= 2 && p.z < 5) {
      c.solid[i] = true;
      c.velocity[i] = glm::vec3(0);  // as the LBM leaves a static obstacle
    }
  }
  expectMatchesCpu(c, 4);
}

// With upres 2 the face velocity is the trilinear interpolation of the lattice velocity; on a periodic
// axis (z here, every axis in the next test) it interpolates across the periodic faces.
TEST_F(SmokeTransportTest, FinerSmokeGridOpenFaces) {
  expectMatchesCpu({kOpen, 2, divergentVelocity(kLattice), {}}, 2);
}

TEST_F(SmokeTransportTest, FinerSmokeGridPeriodic) {
  expectMatchesCpu({kPeriodic, 2, divergenceFreeVelocity(kLattice), {}}, 2);
}

TEST_F(SmokeTransportTest, ClosedBoxConservesAndStaysPositive) {
  for (int upres : {1, 2}) {
    SCOPED_TRACE("upres " + std::to_string(upres));
    const SmokeCase c{kClosed, upres, divergentVelocity(kLattice), {}};
    const std::vector<glm::vec2> initial = randomSmoke(kLattice * upres, 5);
    const std::vector<glm::vec2> got = expectMatchesCpu(c, 3);
    for (int component = 0; component < 2; ++component) {
      double before = 0, after = 0, largest = 0, lowest = INFINITY;
      for (size_t i = 0; i < got.size(); ++i) {
        before += initial[i][component];
        after += got[i][component];
        largest = std::max(largest, double(std::abs(got[i][component])));
        lowest = std::min(lowest, double(got[i][component]));
      }
      EXPECT_NEAR(after, before, double(got.size()) * kEpsilon * largest) << "component " << component;
      EXPECT_GE(lowest, -kEpsilon * largest) << "component " << component;
      std::cout << "[ measured ] component " << component << ": Σ before " << before << ", after " << after
                << " (relative " << std::abs(after - before) / before << "); minimum " << lowest << "\n";
    }
  }
}

// Dense: one pass over every cell. Sparse: the decay over the active bricks (all of them after an upload),
// then the inlets set over their box, here the lattice cells [(3, 1, 0), (10, 7, 8)) that hold both inlets.
TEST_F(SmokeTransportTest, SourcesSetInletCellsAndDecayTheRest) {
  for (const bool sparse : {false, true}) {
    SCOPED_TRACE(sparse ? "sparse" : "dense");
    expectSourcesMatchCpu(sparse);
  }
}

void SmokeTransportTest::expectSourcesMatchCpu(bool sparse) {
  const int upres = 2;
  const double decay = 0.9;
  sim::SmokeSettings settings{kLattice, upres, kPeriodic, float(decay)};
  settings.sparse = sparse;
  sim::SmokeTransport transport(context(), pipelineCache(), settings);
  const std::vector<glm::vec2> initial = randomSmoke(kLattice * upres, 6);
  transport.upload(initial);

  // Inlet 1 on a slab of lattice cells, inlet 2 on one cell; the flags say which cells they force.
  std::vector<CellFlags> cells(cellCount(kLattice));
  for (int i = 0; i < int(cells.size()); ++i) {
    const glm::ivec3 p = cellOf(i, kLattice);
    if (p.y == 1 && p.x >= 3 && p.x < 8) cells[i].inlet = 0;
    if (p == glm::ivec3(9, 6, 5)) cells[i].inlet = 1;
  }
  const std::vector<glm::dvec2> inletSmoke = {{1.5, 0.75}, {0.25, 2.0}};
  gpu::Buffer flags = gpu::Buffer::storage(context(), cells.size() * 4, "flags");
  flags.upload(encodeFlags(cells));
  gpu::Buffer params(context(), sizeof(sim::StepParams), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                     gpu::MemoryKind::HostUpload, "step parameters");
  auto* p = static_cast<sim::StepParams*>(params.mapped());
  std::memset(p, 0, sizeof(sim::StepParams));
  for (size_t i = 0; i < inletSmoke.size(); ++i)
    p->inlets[i].smoke = glm::vec4(inletSmoke[i].x, inletSmoke[i].y, 1.0f, 0.0f);
  p->counts = glm::uvec4(0, inletSmoke.size(), 0, 0);

  gpu::Sequence sequence(context());
  transport.recordSources(sequence, params, flags, 0, {glm::ivec3(3, 1, 0), glm::ivec3(10, 7, kLattice.z)});
  sequence.submit();
  const std::vector<glm::vec2> got = transport.download();
  std::vector<glm::dvec2> expected = toDouble(initial);
  applySmokeSources({kLattice, upres, kPeriodic}, cells, inletSmoke, decay, expected);
  double worst = 0;
  for (size_t i = 0; i < got.size(); ++i)
    worst = std::max({worst, std::abs(got[i].x - expected[i].x), std::abs(got[i].y - expected[i].y)});
  EXPECT_LE(worst, 2 * kEpsilon * 2.0) << "one float multiplication per value";
  std::cout << "[ measured ] max |Δ| " << worst << "\n";
}

}  // namespace
}  // namespace sixway::test
