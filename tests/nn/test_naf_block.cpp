// The NAFBlock kernels (shaders/nn/naf_*.comp) against the CPU reference of NAFNet's block, with every
// parameter random and beta, gamma, the LayerNorm affine and the attention nonzero, so no branch is an
// identity; odd sizes and channel counts, expansions other than 2, several workgroups of partial sums.
#include <string>

#include "gpu/sequence.h"
#include "nn/naf_block_kernel.h"
#include "nn/nn_test_support.h"

namespace sixway::test {
namespace {

using nn::Precision;

struct NafCase {
  const char* name;
  int channels, dwExpand, ffnExpand, height, width;
  Precision precision = Precision::Fp32;
  int projection = 0;  // a fused 1x1 conv after the block (an adapter's head)
  nn::Tiling tiling = nn::Tiling::Blocks;
};

void PrintTo(const NafCase& c, std::ostream* os) {
  *os << c.name;
}

// Random parameters in the ranges a trained block has; beta and gamma away from zero, with random signs.
nn::ParameterMap randomParameters(const NafCase& c, std::mt19937& rng) {
  const int ch = c.channels, dw = ch * c.dwExpand, ffn = ch * c.ffnExpand;
  auto conv = [&rng](int out, int in, int taps) {
    const float bound = std::sqrt(3.0f / float(in * taps));
    return randomValues(size_t(out) * in * taps, rng, -bound, bound);
  };
  auto signedAway = [&rng](int n) {
    std::vector<float> v = randomValues(n, rng, 0.2f, 0.6f);
    for (float& x : v) x *= (rng() & 1) ? 1.0f : -1.0f;
    return v;
  };
  return {{"norm1.weight", randomValues(ch, rng, 0.5f, 1.5f)},
          {"norm1.bias", randomValues(ch, rng, -0.2f, 0.2f)},
          {"conv1.weight", conv(dw, ch, 1)},
          {"conv1.bias", randomValues(dw, rng, -0.1f, 0.1f)},
          {"conv2.weight", conv(dw, 1, 9)},
          {"conv2.bias", randomValues(dw, rng, -0.1f, 0.1f)},
          {"sca.weight", conv(dw / 2, dw / 2, 1)},
          {"sca.bias", randomValues(dw / 2, rng, 0.5f, 1.0f)},
          {"conv3.weight", conv(ch, dw / 2, 1)},
          {"conv3.bias", randomValues(ch, rng, -0.1f, 0.1f)},
          {"norm2.weight", randomValues(ch, rng, 0.5f, 1.5f)},
          {"norm2.bias", randomValues(ch, rng, -0.2f, 0.2f)},
          {"conv4.weight", conv(ffn, ch, 1)},
          {"conv4.bias", randomValues(ffn, rng, -0.1f, 0.1f)},
          {"conv5.weight", conv(ch, ffn / 2, 1)},
          {"conv5.bias", randomValues(ch, rng, -0.1f, 0.1f)},
          {"beta", signedAway(ch)},
          {"gamma", signedAway(ch)}};
}

class NafBlockTest : public NnTest, public ::testing::WithParamInterface<NafCase> {};

TEST_P(NafBlockTest, MatchesCpuReference) {
  const NafCase& c = GetParam();
  std::mt19937 rng(std::hash<std::string>{}(c.name) & 0xffff);
  const CpuMap input = randomMap(c.channels, c.height, c.width, rng);
  nn::ParameterMap parameters = randomParameters(c, rng);
  const float eps = 1e-6f;
  CpuMap expected = nafBlock(input, parameters, eps);
  if (c.projection) {
    parameters["projection.weight"] = randomValues(size_t(c.projection) * c.channels, rng, -0.5f, 0.5f);
    parameters["projection.bias"] = randomValues(c.projection, rng, -0.5f, 0.5f);
    expected =
        conv2d(expected, parameters["projection.weight"], parameters["projection.bias"], c.projection, 1, 1);
  }

  const nn::NafShape shape{uint32_t(c.width), uint32_t(c.height), c.channels, c.dwExpand, c.ffnExpand, eps,
                           c.projection};
  nn::NafBlockKernel kernel(setup(c.precision, c.tiling), shape, parameters, c.name);
  const nn::FeatureMap in = upload(input, c.precision);
  nn::FeatureMap out = empty(shape.output(), c.precision);
  gpu::Sequence sequence(context());
  kernel.record(sequence, in, out);
  sequence.submit();
  const double tolerance = c.precision == Precision::Fp16 ? kFp16Tolerance : kFp32Tolerance;
  EXPECT_TRUE(allClose(out.download(), expected.values, tolerance, tolerance));
}

INSTANTIATE_TEST_SUITE_P(
    Layers, NafBlockTest,
    ::testing::Values(NafCase{"c5_odd", 5, 2, 2, 9, 13}, NafCase{"c6_dw3", 6, 3, 2, 11, 7},
                      NafCase{"c7_ffn4", 7, 2, 4, 10, 11}, NafCase{"c16_many_workgroups", 16, 2, 2, 37, 40},
                      NafCase{"c8_fp16", 8, 2, 2, 12, 9, Precision::Fp16},
                      NafCase{"c7_head2", 7, 2, 2, 13, 10, Precision::Fp32, 2},
                      NafCase{"c16_head5", 16, 2, 2, 9, 11, Precision::Fp32, 5},
                      NafCase{"c7_head2_pixels", 7, 2, 2, 13, 10, Precision::Fp32, 2, nn::Tiling::Pixels},
                      NafCase{"c24_pixels_fp16", 24, 2, 2, 9, 11, Precision::Fp16, 0, nn::Tiling::Pixels}),
    [](const ::testing::TestParamInfo<NafCase>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace sixway::test
