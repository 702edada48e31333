// shaders/nn/conv2d.comp and conv_transpose2x2.comp against the CPU reference on random inputs: odd sizes,
// channel counts that are not multiples of 4, concatenated inputs, every activation, weight chunks, both
// dispatch modes, fp32 and fp16 maps.
#include <cmath>
#include <string>

#include "gpu/sequence.h"
#include "nn/conv_kernel.h"
#include "nn/nn_test_support.h"

namespace sixway::test {
namespace {

using nn::Activation;
using nn::Precision;

struct ConvCase {
  const char* name;
  std::vector<int> inputs;
  int outChannels, kernel, stride, height, width;
  Activation activation = Activation::None;
  bool transposed = false;
  Precision precision = Precision::Fp32;
  int rows = 0;    // output rows per invocation; 0: the kernel's choice
  int pixels = 0;  // output pixels along x per invocation; 0: the kernel's choice
  nn::Tiling tiling = nn::Tiling::Blocks;
};

void PrintTo(const ConvCase& c, std::ostream* os) {
  *os << c.name;
}

class ConvTest : public NnTest, public ::testing::WithParamInterface<ConvCase> {};

TEST_P(ConvTest, MatchesCpuReference) {
  const ConvCase& c = GetParam();
  std::mt19937 rng(std::hash<std::string>{}(c.name) & 0xffff);
  std::vector<CpuMap> inputs;
  for (int channels : c.inputs) inputs.push_back(randomMap(channels, c.height, c.width, rng));
  CpuMap all = inputs[0];
  for (size_t i = 1; i < inputs.size(); ++i) all = concat(all, inputs[i]);
  const int taps = c.transposed ? 4 : c.kernel * c.kernel;
  const float bound = std::sqrt(3.0f / float(all.channels * taps));
  const std::vector<float> weight =
      randomValues(size_t(all.channels) * c.outChannels * taps, rng, -bound, bound);
  const std::vector<float> bias = randomValues(c.outChannels, rng, -0.5f, 0.5f);
  const float slope = 0.15f;

  CpuMap expected = c.transposed ? convTranspose2x2(all, weight, bias, c.outChannels)
                                 : conv2d(all, weight, bias, c.outChannels, c.kernel, c.stride);
  expected = activate(expected, c.activation, slope);

  nn::ConvShape shape{uint32_t(c.width), uint32_t(c.height), c.inputs, c.outChannels, c.kernel, c.stride,
                      c.transposed,      c.activation,       slope,    c.rows,        c.pixels};
  nn::ConvKernel kernel(setup(c.precision, c.tiling), shape, weight, bias, c.name);
  std::vector<nn::FeatureMap> maps;
  for (const CpuMap& input : inputs) maps.push_back(upload(input, c.precision));
  std::vector<const nn::FeatureMap*> pointers;
  for (const nn::FeatureMap& map : maps) pointers.push_back(&map);
  nn::FeatureMap output = empty(shape.output(), c.precision);
  ASSERT_EQ(shape.output(),
            (nn::MapShape{uint32_t(expected.width), uint32_t(expected.height), uint32_t(expected.channels)}));
  gpu::Sequence sequence(context());
  kernel.record(sequence, pointers, output);
  sequence.submit();
  const double tolerance = c.precision == Precision::Fp16 ? kFp16Tolerance : kFp32Tolerance;
  EXPECT_TRUE(allClose(output.download(), expected.values, tolerance, tolerance));
}

// Output rows and pixels per invocation are forced on some small maps (the kernel would choose fewer: on maps
// this small both tilings shrink the blocks towards one pixel, conv_kernel.cpp) so that blocks overhang the
// map; 40 and 36 input channels need a loop of unrolled slices plus a remainder, and 40 -> 48 needs two
// weight chunks. 2 x 2 blocks are forced once; an 8 x 8 map of 24 channels is a deep UNet level as the kernel
// tiles it (1-pixel blocks).
using C = ConvCase;
const nn::Tiling kPixels = nn::Tiling::Pixels;
const Activation kRelu = Activation::Relu, kLeaky = Activation::LeakyRelu, kGelu = Activation::Gelu,
                 kSilu = Activation::Silu, kNone = Activation::None;
INSTANTIATE_TEST_SUITE_P(Layers, ConvTest,
                         ::testing::Values(C{.name = "conv3x3_3to5_relu",
                                             .inputs = {3},
                                             .outChannels = 5,
                                             .kernel = 3,
                                             .stride = 1,
                                             .height = 13,
                                             .width = 11,
                                             .activation = kRelu},
                                           C{.name = "conv3x3_rows8_overhanging",
                                             .inputs = {6},
                                             .outChannels = 5,
                                             .kernel = 3,
                                             .stride = 1,
                                             .height = 13,
                                             .width = 11,
                                             .activation = kRelu,
                                             .rows = 8,
                                             .pixels = 4},
                                           C{.name = "conv3x3_rows4_concat",
                                             .inputs = {4, 3},
                                             .outChannels = 9,
                                             .kernel = 3,
                                             .stride = 1,
                                             .height = 10,
                                             .width = 7,
                                             .activation = kSilu,
                                             .rows = 4},
                                           C{.name = "conv3x3_stride2_7to6_leaky",
                                             .inputs = {7},
                                             .outChannels = 6,
                                             .kernel = 3,
                                             .stride = 2,
                                             .height = 9,
                                             .width = 13,
                                             .activation = kLeaky},
                                           C{.name = "conv3x3_stride2_rows8",
                                             .inputs = {5},
                                             .outChannels = 7,
                                             .kernel = 3,
                                             .stride = 2,
                                             .height = 21,
                                             .width = 11,
                                             .activation = kRelu,
                                             .rows = 8},
                                           C{.name = "conv3x3_stride2_even",
                                             .inputs = {4},
                                             .outChannels = 8,
                                             .kernel = 3,
                                             .stride = 2,
                                             .height = 12,
                                             .width = 16,
                                             .activation = kRelu},
                                           C{.name = "conv3x3_concat_3_5to7_gelu",
                                             .inputs = {3, 5},
                                             .outChannels = 7,
                                             .kernel = 3,
                                             .stride = 1,
                                             .height = 7,
                                             .width = 9,
                                             .activation = kGelu},
                                           C{.name = "conv3x3_concat_slices_20_12to6",
                                             .inputs = {20, 12},
                                             .outChannels = 6,
                                             .kernel = 3,
                                             .stride = 1,
                                             .height = 9,
                                             .width = 10,
                                             .activation = kRelu,
                                             .rows = 2},
                                           C{.name = "conv1x1_concat_6_3to9_silu",
                                             .inputs = {6, 3},
                                             .outChannels = 9,
                                             .kernel = 1,
                                             .stride = 1,
                                             .height = 5,
                                             .width = 11,
                                             .activation = kSilu},
                                           C{.name = "conv1x1_stride2_5to3",
                                             .inputs = {5},
                                             .outChannels = 3,
                                             .kernel = 1,
                                             .stride = 2,
                                             .height = 10,
                                             .width = 7,
                                             .activation = kNone},
                                           C{.name = "conv3x3_40to48_chunks",
                                             .inputs = {40},
                                             .outChannels = 48,
                                             .kernel = 3,
                                             .stride = 1,
                                             .height = 6,
                                             .width = 10,
                                             .activation = kRelu,
                                             .rows = 2},
                                           C{.name = "conv3x3_stride2_36to5",
                                             .inputs = {36},
                                             .outChannels = 5,
                                             .kernel = 3,
                                             .stride = 2,
                                             .height = 11,
                                             .width = 17,
                                             .activation = kSilu},
                                           C{.name = "conv3x3_fp16",
                                             .inputs = {5, 6},
                                             .outChannels = 7,
                                             .kernel = 3,
                                             .stride = 1,
                                             .height = 9,
                                             .width = 10,
                                             .activation = kRelu,
                                             .precision = Precision::Fp16,
                                             .rows = 8},
                                           C{.name = "conv3x3_stride2_fp16",
                                             .inputs = {9},
                                             .outChannels = 6,
                                             .kernel = 3,
                                             .stride = 2,
                                             .height = 11,
                                             .width = 9,
                                             .activation = kGelu,
                                             .precision = Precision::Fp16},
                                           C{.name = "transposed_7to5",
                                             .inputs = {7},
                                             .outChannels = 5,
                                             .kernel = 2,
                                             .stride = 2,
                                             .height = 6,
                                             .width = 9,
                                             .activation = kNone,
                                             .transposed = true},
                                           C{.name = "transposed_12to10_relu",
                                             .inputs = {12},
                                             .outChannels = 10,
                                             .kernel = 2,
                                             .stride = 2,
                                             .height = 5,
                                             .width = 7,
                                             .activation = kRelu,
                                             .transposed = true,
                                             .pixels = 8},
                                           C{.name = "transposed_fp16",
                                             .inputs = {6},
                                             .outChannels = 3,
                                             .kernel = 2,
                                             .stride = 2,
                                             .height = 7,
                                             .width = 5,
                                             .activation = kNone,
                                             .transposed = true,
                                             .precision = Precision::Fp16},
                                           C{.name = "pixels_concat_40_3to10",
                                             .inputs = {40, 3},
                                             .outChannels = 10,
                                             .kernel = 3,
                                             .stride = 1,
                                             .height = 9,
                                             .width = 7,
                                             .activation = kRelu,
                                             .tiling = kPixels},
                                           C{.name = "pixels_stride2",
                                             .inputs = {5},
                                             .outChannels = 6,
                                             .kernel = 3,
                                             .stride = 2,
                                             .height = 11,
                                             .width = 9,
                                             .activation = kLeaky,
                                             .tiling = kPixels},
                                           C{.name = "blocks_2x2_overhanging",
                                             .inputs = {6},
                                             .outChannels = 5,
                                             .kernel = 3,
                                             .stride = 1,
                                             .height = 9,
                                             .width = 7,
                                             .activation = kRelu,
                                             .rows = 2,
                                             .pixels = 2},
                                           C{.name = "blocks_deep_level_8x8",
                                             .inputs = {24},
                                             .outChannels = 12,
                                             .kernel = 3,
                                             .stride = 1,
                                             .height = 8,
                                             .width = 8,
                                             .activation = kRelu},
                                           C{.name = "pixels_transposed_fp16",
                                             .inputs = {12},
                                             .outChannels = 10,
                                             .kernel = 2,
                                             .stride = 2,
                                             .height = 5,
                                             .width = 7,
                                             .activation = kRelu,
                                             .transposed = true,
                                             .precision = Precision::Fp16,
                                             .tiling = kPixels}),
                         [](const ::testing::TestParamInfo<ConvCase>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace
}  // namespace sixway::test
