// Poiseuille flow: a channel between no-slip walls at y = 0 and y = H (half-way bounce-back),
// periodic along the flow, driven by a body force g: u(y) = g/(2ν) · y (H − y).
#include <gtest/gtest.h>

#include <cmath>

#include "sim/simulation.h"
#include "support/gpu_fixture.h"
#include "validation/flow_scene.h"

namespace sixway::test {
namespace {

class Poiseuille : public GpuTest, public ::testing::WithParamInterface<double> {};

void expectAnalyticProfile(const gpu::Context& context, const gpu::PipelineCache& cache, double nu,
                           const std::string& storage) {
  const int height = 16;
  const double g = 1e-6;
  scene::Scene scene =
      latticeScene(4, height, 1, nu, "periodic",
                   {{"boundaries", {{"y-", "no_slip"}, {"y+", "no_slip"}}},
                    {"fluid", {{"body_force", {g, 0.0, 0.0}}, {"population_storage", storage}}}});
  sim::Simulation simulation(context, cache, scene);
  // Five diffusion times H²/ν: the slowest start-up mode has decayed by e^{−5π²}.
  simulation.advance(uint32_t(5 * height * height / nu));
  const std::vector<glm::vec4> macro = simulation.lbm().macro().download<glm::vec4>();
  double error = 0, norm = 0;
  for (int y = 0; y < height; ++y) {
    const double exact = g / (2 * nu) * (y + 0.5) * (height - y - 0.5);
    const double u = macro[size_t(y) * 4].x;  // column x = 0
    error += (u - exact) * (u - exact);
    norm += exact * exact;
  }
  const double relativeL2 = std::sqrt(error / norm);
  ::testing::Test::RecordProperty("relative_l2", std::to_string(relativeL2));
  std::printf("%s, nu %.4f: relative L2 error %.5f\n", storage.c_str(), nu, relativeL2);
  EXPECT_LT(relativeL2, 0.02) << "relative L2 error of the profile";
}

TEST_P(Poiseuille, ProfileMatchesTheAnalyticOne) {
  expectAnalyticProfile(context(), pipelineCache(), GetParam(), "fp32");
}

TEST_P(Poiseuille, ProfileMatchesTheAnalyticOneWithFp16Populations) {
  expectAnalyticProfile(context(), pipelineCache(), GetParam(), "fp16");
}

// τ = 0.6 and τ = 1.
INSTANTIATE_TEST_SUITE_P(Viscosities, Poiseuille, ::testing::Values(1.0 / 30, 1.0 / 6));

}  // namespace
}  // namespace sixway::test
