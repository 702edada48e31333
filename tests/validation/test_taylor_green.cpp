// Taylor–Green vortex (2D, periodic): u = U₀(−cos kx sin ky, sin kx cos ky) decays as e^{−ν(kx²+ky²)t},
// so the kinetic energy decays at 2ν(kx²+ky²). The fitted rate must match within 1%, with 32-bit and with
// 16-bit population storage.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/simulation.h"
#include "support/gpu_fixture.h"
#include "validation/flow_scene.h"

namespace sixway::test {
namespace {

class TaylorGreen : public GpuTest, public ::testing::WithParamInterface<double> {};

double kineticEnergy(const sim::Simulation& simulation) {
  double energy = 0;
  for (const glm::vec4& m : simulation.lbm().macro().download<glm::vec4>())
    energy += 0.5 * double(m.w) * glm::dot(glm::vec3(m), glm::vec3(m));
  return energy;
}

void expectAnalyticDecay(const gpu::Context& context, const gpu::PipelineCache& cache, double nu,
                         const std::string& storage) {
  const int n = 64;
  const double u0 = 0.02, k = 2 * std::numbers::pi / n;
  sim::Simulation simulation(context, cache,
                             latticeScene(n, n, 1, nu, "periodic", populationStorage(storage)));
  std::vector<glm::vec3> velocity;
  std::vector<float> density;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const double px = k * (x + 0.5), py = k * (y + 0.5);
      velocity.emplace_back(-u0 * std::cos(px) * std::sin(py), u0 * std::sin(px) * std::cos(py), 0.0);
      // ρ = 1 + p / c_s², p = −(U₀²/4)(cos 2kx + cos 2ky)
      density.push_back(float(1 - 0.75 * u0 * u0 * (std::cos(2 * px) + std::cos(2 * py))));
    }
  simulation.setFlow(velocity, density);

  // Least-squares slope of ln E over time, after the start-up of the non-equilibrium part.
  const int stepsBetween = 50, samples = 16;
  simulation.advance(100);
  double st = 0, sy = 0, stt = 0, sty = 0;
  for (int i = 0; i < samples; ++i) {
    const double t = double(simulation.step()), y = std::log(kineticEnergy(simulation));
    st += t, sy += y, stt += t * t, sty += t * y;
    simulation.advance(stepsBetween);
  }
  const double slope = (samples * sty - st * sy) / (samples * stt - st * st);
  const double expected = 2 * nu * 2 * k * k;
  ::testing::Test::RecordProperty("measured_rate", std::to_string(-slope));
  ::testing::Test::RecordProperty("analytic_rate", std::to_string(expected));
  EXPECT_NEAR(-slope / expected, 1.0, 0.01) << "energy decay rate " << -slope << ", analytic " << expected;
}

TEST_P(TaylorGreen, EnergyDecaysAtTheAnalyticRate) {
  expectAnalyticDecay(context(), pipelineCache(), GetParam(), "fp32");
}

TEST_P(TaylorGreen, EnergyDecaysAtTheAnalyticRateWithFp16Populations) {
  expectAnalyticDecay(context(), pipelineCache(), GetParam(), "fp16");
}

// τ = 0.53, 0.56 and 0.8: from nearly inviscid to well resolved.
INSTANTIATE_TEST_SUITE_P(Viscosities, TaylorGreen, ::testing::Values(0.01, 0.02, 0.1));

}  // namespace
}  // namespace sixway::test
