// shaders/nn/conv2d_matrix.comp against the CPU reference on random fp16 maps: channel counts that are not
// multiples of 4 or of a matrix tile, concatenated inputs, stride 2 on odd and even sizes, 1x1 kernels, maps
// whose pixels do not fill the last workgroup, a layer whose output channels are split over workgroups (a
// small map) and one of many K chunks. Skipped on a device without cooperative matrices (lavapipe).
#include <cmath>
#include <string>

#include "gpu/context.h"
#include "gpu/sequence.h"
#include "nn/conv_matrix_kernel.h"
#include "nn/nn_test_support.h"

namespace sixway::test {
namespace {

using nn::Activation;
using nn::Precision;

struct MatrixCase {
  const char* name;
  std::vector<int> inputs;
  int outChannels, kernel, stride, height, width;
  Activation activation = Activation::None;
};

void PrintTo(const MatrixCase& c, std::ostream* os) {
  *os << c.name;
}

class ConvMatrixTest : public NnTest, public ::testing::WithParamInterface<MatrixCase> {};

TEST_P(ConvMatrixTest, MatchesCpuReference) {
  if (!context().capabilities().cooperativeMatrix)
    GTEST_SKIP() << context().properties().deviceName << " has no cooperative matrices sixway can use";
  const MatrixCase& c = GetParam();
  std::mt19937 rng(std::hash<std::string>{}(c.name) & 0xffff);
  std::vector<CpuMap> inputs;
  for (int channels : c.inputs) inputs.push_back(randomMap(channels, c.height, c.width, rng));
  CpuMap all = inputs[0];
  for (size_t i = 1; i < inputs.size(); ++i) all = concat(all, inputs[i]);
  const int taps = c.kernel * c.kernel;
  const float bound = std::sqrt(3.0f / float(all.channels * taps));
  const std::vector<float> weight =
      randomValues(size_t(all.channels) * c.outChannels * taps, rng, -bound, bound);
  const std::vector<float> bias = randomValues(c.outChannels, rng, -0.5f, 0.5f);
  const float slope = 0.15f;
  const CpuMap expected =
      activate(conv2d(all, weight, bias, c.outChannels, c.kernel, c.stride), c.activation, slope);

  nn::ConvShape shape{uint32_t(c.width),
                      uint32_t(c.height),
                      c.inputs,
                      c.outChannels,
                      c.kernel,
                      c.stride,
                      false,
                      c.activation,
                      slope};
  nn::ConvMatrixKernel kernel(setup(Precision::Fp16, nn::Tiling::Matrix), shape, weight, bias, c.name);
  std::vector<nn::FeatureMap> maps;
  for (const CpuMap& input : inputs) maps.push_back(upload(input, Precision::Fp16));
  std::vector<const nn::FeatureMap*> pointers;
  for (const nn::FeatureMap& map : maps) pointers.push_back(&map);
  nn::FeatureMap output = empty(shape.output(), Precision::Fp16);
  gpu::Sequence sequence(context());
  kernel.record(sequence, pointers, output);
  sequence.submit();
  const std::vector<float> actual = output.download();
  std::printf("%s: NMSE %.2e, max-abs %.2e\n", c.name, nmse(actual, expected.values),
              maxAbsError(actual, expected.values));
  EXPECT_TRUE(allClose(actual, expected.values, kFp16Tolerance, kFp16Tolerance));
}

using C = MatrixCase;
INSTANTIATE_TEST_SUITE_P(
    Layers, ConvMatrixTest,
    ::testing::Values(C{"conv3x3_3to5_relu", {3}, 5, 3, 1, 13, 11, Activation::Relu},
                      C{"conv3x3_concat_16_16to16_leaky", {16, 16}, 16, 3, 1, 20, 18, Activation::LeakyRelu},
                      C{"conv3x3_concat_7_5to9_silu", {7, 5}, 9, 3, 1, 10, 7, Activation::Silu},
                      C{"conv3x3_stride2_24to48_gelu", {24}, 48, 3, 2, 33, 31, Activation::Gelu},
                      C{"conv3x3_stride2_even_8to12", {8}, 12, 3, 2, 16, 24},
                      C{"conv1x1_24to8", {24}, 8, 1, 1, 9, 15},
                      C{"conv1x1_5to30_relu", {5}, 30, 1, 1, 17, 5, Activation::Relu},
                      C{"conv3x3_96to96_split", {96}, 96, 3, 1, 16, 16, Activation::LeakyRelu},
                      C{"conv3x3_40to130_many_tiles", {40}, 130, 3, 1, 9, 7, Activation::Gelu},
                      C{"conv3x3_24to24_large", {24}, 24, 3, 1, 67, 65, Activation::LeakyRelu}),
    [](const ::testing::TestParamInfo<MatrixCase>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace sixway::test
