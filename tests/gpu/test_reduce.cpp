// gpu/reduce_stats.comp against a CPU reference (double precision) on random data.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "gpu/buffer.h"
#include "gpu/reduce_stats.h"
#include "gpu/sequence.h"
#include "support/gpu_fixture.h"

namespace sixway::test {
namespace {

struct CpuStats {
  double sum = 0, sumAbs = 0;
  float minimum = std::numeric_limits<float>::infinity();
  float maximum = -std::numeric_limits<float>::infinity();
  float maxAbs = -1;
  uint32_t maxAbsIndex = 0xffffffffu, nonFinite = 0, firstNonFinite = 0xffffffffu;
};

CpuStats cpuStats(const std::vector<float>& values) {
  CpuStats s;
  for (uint32_t i = 0; i < values.size(); ++i) {
    const float v = values[i];
    if (!std::isfinite(v)) {
      if (s.nonFinite++ == 0) s.firstNonFinite = i;
      continue;
    }
    s.sum += v;
    s.sumAbs += std::fabs(v);
    s.minimum = std::min(s.minimum, v);
    s.maximum = std::max(s.maximum, v);
    if (std::fabs(v) > s.maxAbs) {  // strict: the first of equal values wins, as on the GPU
      s.maxAbs = std::fabs(v);
      s.maxAbsIndex = i;
    }
  }
  return s;
}

class ReduceStatsTest : public GpuTest, public ::testing::WithParamInterface<uint32_t> {
 protected:
  gpu::Stats reduceOnGpu(const std::vector<float>& values) {
    gpu::Buffer buffer = gpu::Buffer::storage(context(), values.size() * sizeof(float), "values");
    buffer.upload(values);
    gpu::ReduceStats reduce(context(), pipelineCache(), values.size());
    gpu::Sequence sequence(context());
    reduce.record(sequence, buffer, static_cast<uint32_t>(values.size()));
    sequence.submit();
    return reduce.result();
  }
};

TEST_P(ReduceStatsTest, MatchesCpuReference) {
  const uint32_t n = GetParam();
  std::mt19937 rng(n);
  std::normal_distribution<float> normal(0.3f, 2.0f);
  std::vector<float> values(n);
  for (float& v : values) v = normal(rng);

  const gpu::Stats gpu = reduceOnGpu(values);
  const CpuStats cpu = cpuStats(values);
  EXPECT_EQ(gpu.count, n);
  EXPECT_EQ(gpu.minimum, cpu.minimum);
  EXPECT_EQ(gpu.maximum, cpu.maximum);
  EXPECT_EQ(gpu.maxAbs, cpu.maxAbs);
  EXPECT_EQ(gpu.maxAbsIndex, cpu.maxAbsIndex);
  EXPECT_EQ(gpu.nonFinite, 0u);
  EXPECT_EQ(gpu.firstNonFinite, 0xffffffffu);
  // Pairwise float summation: error bound ~ log2(n) · eps · Σ|v|.
  const double tolerance = (std::log2(double(n)) + 1) * 6e-8 * cpu.sumAbs;
  EXPECT_NEAR(gpu.sum, cpu.sum, tolerance);
}

// Sizes around the 2048-value workgroup tile, and ones that need two and three passes.
INSTANTIATE_TEST_SUITE_P(Sizes, ReduceStatsTest,
                         ::testing::Values(1u, 7u, 2047u, 2048u, 2049u, 300001u, 4200000u));

TEST_F(ReduceStatsTest, FindsTheFirstNonFiniteValue) {
  std::vector<float> values(70000, 1.0f);
  values[65537] = std::numeric_limits<float>::quiet_NaN();
  values[40000] = std::numeric_limits<float>::infinity();
  values[69999] = -std::numeric_limits<float>::infinity();
  values[123] = -7.0f;
  const gpu::Stats gpu = reduceOnGpu(values);
  EXPECT_EQ(gpu.nonFinite, 3u);
  EXPECT_EQ(gpu.firstNonFinite, 40000u);
  EXPECT_EQ(gpu.sum, 70000.0f - 3.0f - 8.0f);
  EXPECT_EQ(gpu.minimum, -7.0f);
  EXPECT_EQ(gpu.maxAbsIndex, 123u);
}

}  // namespace
}  // namespace sixway::test

namespace sixway::test {
namespace {

TEST_F(ReduceStatsTest, LengthsOfStridedVectors) {
  // vec4 (x, y, z, w) per value; the statistic is |xyz|, w is skipped.
  const uint32_t n = 5001;
  std::vector<float> values(4 * n);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  for (float& v : values) v = uniform(rng);
  values[4 * 777 + 3] = 1e9f;  // in w: must not count
  gpu::Buffer buffer = gpu::Buffer::storage(context(), values.size() * 4, "vec4s");
  buffer.upload(values);
  gpu::ReduceStats reduce(context(), pipelineCache(), n, {4, 3});
  gpu::Sequence sequence(context());
  reduce.record(sequence, buffer, n);
  sequence.submit();
  const gpu::Stats stats = reduce.result();
  float longest = 0;
  uint32_t where = 0;
  double sum = 0;
  for (uint32_t i = 0; i < n; ++i) {
    const float length = std::sqrt(values[4 * i] * values[4 * i] + values[4 * i + 1] * values[4 * i + 1] +
                                   values[4 * i + 2] * values[4 * i + 2]);
    sum += length;
    if (length > longest) longest = length, where = i;
  }
  EXPECT_NEAR(stats.maxAbs, longest, 1e-6f);
  EXPECT_EQ(stats.maxAbsIndex, where);
  EXPECT_NEAR(stats.sum, sum, 1e-3);
}

}  // namespace
}  // namespace sixway::test
