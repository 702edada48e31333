#include "nn/nn_test_support.h"

#include <cmath>
#include <sstream>

namespace sixway::test {

std::vector<float> randomValues(size_t count, std::mt19937& rng, float low, float high) {
  std::uniform_real_distribution<float> uniform(low, high);
  std::vector<float> values(count);
  for (float& v : values) v = uniform(rng);
  return values;
}

CpuMap randomMap(int channels, int height, int width, std::mt19937& rng) {
  CpuMap map(channels, height, width);
  map.values = randomValues(map.values.size(), rng);
  return map;
}

::testing::AssertionResult allClose(const std::vector<float>& actual, const std::vector<float>& expected,
                                    double absolute, double relative) {
  if (actual.size() != expected.size())
    return ::testing::AssertionFailure() << actual.size() << " values, expected " << expected.size();
  size_t bad = 0, worst = 0;
  double worstError = -1.0;
  for (size_t i = 0; i < actual.size(); ++i) {
    const double error = std::fabs(double(actual[i]) - expected[i]);
    const bool ok = error <= absolute || error <= relative * std::fabs(expected[i]);  // NaN fails both
    if (!ok) ++bad;
    if (!ok && !(error <= worstError)) {
      worstError = error;
      worst = i;
    }
  }
  if (bad == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << bad << " of " << actual.size() << " values off; worst at " << worst
                                       << ": " << actual[worst] << " vs " << expected[worst];
}

double nmse(const std::vector<float>& actual, const std::vector<float>& expected) {
  double error = 0.0, energy = 0.0;
  for (size_t i = 0; i < expected.size(); ++i) {
    error += (double(actual[i]) - expected[i]) * (double(actual[i]) - expected[i]);
    energy += double(expected[i]) * expected[i];
  }
  return error / energy;
}

double maxAbsError(const std::vector<float>& actual, const std::vector<float>& expected) {
  double worst = 0.0;
  for (size_t i = 0; i < expected.size(); ++i)
    worst = std::max(worst, std::fabs(double(actual[i]) - expected[i]));
  return worst;
}

}  // namespace sixway::test
