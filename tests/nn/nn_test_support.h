#pragma once
// Shared by the nn tests: random inputs, tolerance checks, and moving CPU maps to and from feature maps.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "nn/cpu_reference.h"
#include "nn/feature_map.h"
#include "nn/kernel.h"
#include "support/gpu_fixture.h"

namespace sixway::test {

std::vector<float> randomValues(size_t count, std::mt19937& rng, float low = -1.0f, float high = 1.0f);
CpuMap randomMap(int channels, int height, int width, std::mt19937& rng);

// Every element within `absolute` or within `relative` of the expected value (abs-or-relative tolerance).
::testing::AssertionResult allClose(const std::vector<float>& actual, const std::vector<float>& expected,
                                    double absolute, double relative);
// Normalised mean squared error sum((a - e)^2) / sum(e^2), and the largest |a - e|.
double nmse(const std::vector<float>& actual, const std::vector<float>& expected);
double maxAbsError(const std::vector<float>& actual, const std::vector<float>& expected);

// Layer tolerances: fp32 maps abs-or-rel 1e-3 (the bound); fp16 maps store 11-bit mantissas, so a
// value and every input it is made of may be off by 2^-11 relative: 1e-2 abs-or-rel covers that with margin.
constexpr double kFp32Tolerance = 1e-3;
constexpr double kFp16Tolerance = 1e-2;

class NnTest : public GpuTest {
 protected:
  nn::KernelSetup setup(nn::Precision precision = nn::Precision::Fp32,
                        nn::Tiling tiling = nn::Tiling::Blocks) {
    static nn::PipelinePool pool(context(), pipelineCache());  // destroyed before the context
    return {&context(), &pool, precision, tiling};
  }
  nn::FeatureMap upload(const CpuMap& map, nn::Precision precision = nn::Precision::Fp32,
                        const char* name = "in") {
    nn::FeatureMap feature(context(), {uint32_t(map.width), uint32_t(map.height), uint32_t(map.channels)},
                           precision, name);
    feature.upload(map.values);
    return feature;
  }
  nn::FeatureMap empty(const nn::MapShape& shape, nn::Precision precision = nn::Precision::Fp32) {
    return nn::FeatureMap(context(), shape, precision, "out");
  }
};

}  // namespace sixway::test
