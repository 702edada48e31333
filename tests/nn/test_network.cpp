// The whole network built from a weights file against what PyTorch (tools/nn/sixway_net.py) computes from it:
// tests/data/nn/*_vectors.safetensors hold a guide, the packed lightmaps and intermediate feature maps.
// fp32 maps: NMSE <= 1e-6 on every compared tensor (measured: about 1e-11, max-abs below 1e-4; each
// comparison prints both). fp16 maps round every layer's output to 11 bits; through ~25 layers of an
// untrained network (LayerNorm amplifies the rounding of nearly constant pixels) that measures up to 6e-4:
// the bound is NMSE <= 1e-3.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gpu/image.h"
#include "gpu/sequence.h"
#include "io/safetensors.h"
#include "nn/network.h"
#include "nn/nn_test_support.h"

namespace sixway::test {
namespace {

using nn::Precision;

struct ParityCase {
  const char* network;
  Precision precision = Precision::Fp32;
  bool fuseProjections = true;
  nn::Tiling tiling = nn::Tiling::Device;
  bool emission = true;  // false: the lightmaps' emissive is 0 (NetworkOptions::emission)
};

std::string caseName(const ParityCase& c) {
  return std::string(c.network) + (c.precision == Precision::Fp16 ? "_fp16" : "_fp32") +
         (c.fuseProjections ? "" : "_unfused") +
         (c.tiling == nn::Tiling::Pixels   ? "_pixels"
          : c.tiling == nn::Tiling::Matrix ? "_matrix"
                                           : "") +
         (c.emission ? "" : "_no_emission");
}

void PrintTo(const ParityCase& c, std::ostream* os) {
  *os << caseName(c);
}

// Channel-major planes of the RGBA texels of an RGBA32F image.
std::vector<float> planes(const std::vector<float>& rgba, size_t pixels) {
  std::vector<float> out(rgba.size());
  for (size_t p = 0; p < pixels; ++p)
    for (size_t c = 0; c < 4; ++c) out[c * pixels + p] = rgba[p * 4 + c];
  return out;
}

class NetworkParity : public NnTest, public ::testing::WithParamInterface<ParityCase> {
 protected:
  void expectMatches(const std::string& what, const std::vector<float>& actual,
                     const std::vector<float>& expected) {
    const double limit = GetParam().precision == Precision::Fp16 ? 1e-3 : 1e-6;
    const double error = nmse(actual, expected), worst = maxAbsError(actual, expected);
    std::printf("  %-28s NMSE %.2e  max-abs %.2e\n", what.c_str(), error, worst);
    EXPECT_LE(error, limit) << what << " (max-abs " << worst << ")";
  }
};

TEST_P(NetworkParity, MatchesPyTorch) {
  const ParityCase& c = GetParam();
  if (c.tiling == nn::Tiling::Matrix && !context().capabilities().cooperativeMatrix)
    GTEST_SKIP() << context().properties().deviceName << " has no cooperative matrices sixway can use";
  const auto data = std::filesystem::path(SIXWAY_TEST_DATA_DIR) / "nn";
  const io::SafetensorsFile weights = io::readSafetensors(data / (std::string(c.network) + ".safetensors"));
  const io::SafetensorsFile vectors =
      io::readSafetensors(data / (std::string(c.network) + "_vectors.safetensors"));
  const io::Tensor& input = vectors.at("input");
  const uint32_t height = uint32_t(input.shape[1]), width = uint32_t(input.shape[2]);
  const size_t pixels = size_t(width) * height;

  // The guide's first 4 channels into an RGBA image, a 5th (the emission) into an R32F one.
  std::vector<float> rgba(pixels * 4, 0.0f), emitted(pixels, 0.0f);
  const std::vector<float> guideValues = input.toFloat();
  const size_t channels = size_t(input.shape[0]);
  for (size_t p = 0; p < pixels; ++p) {
    for (size_t ch = 0; ch < std::min<size_t>(channels, 4); ++ch)
      rgba[p * 4 + ch] = guideValues[ch * pixels + p];
    if (channels > 4) emitted[p] = guideValues[4 * pixels + p];
  }
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  gpu::Image guide(context(), {width, height, 1, VK_FORMAT_R32G32B32A32_SFLOAT, usage, "guide"});
  guide.upload(std::as_bytes(std::span(rgba)));
  gpu::Image emission(context(), {width, height, 1, VK_FORMAT_R32_SFLOAT, usage, "guide emission"});
  emission.upload(std::as_bytes(std::span(emitted)));
  gpu::Image a(context(), {width, height, 1, VK_FORMAT_R32G32B32A32_SFLOAT, usage, "lightmap A"});
  gpu::Image b(context(), {width, height, 1, VK_FORMAT_R32G32B32A32_SFLOAT, usage, "lightmap B"});

  nn::NetworkOptions options{c.precision, c.fuseProjections, c.tiling, c.emission};
  if (vectors.contains("albedo")) options.albedo = vectors.at("albedo").toFloat().at(0);
  nn::Network network(context(), pipelineCache(), weights, width, height, options);
  EXPECT_EQ(network.readsAlbedo(), vectors.contains("albedo"));
  gpu::Sequence sequence(context(), network.stageCount());
  network.record(sequence, {guide, channels > 4 ? &emission : nullptr}, a, b, true);
  sequence.submit();
  const std::vector<float> first = a.download<float>();
  sequence.submit();  // replayed: the same result
  EXPECT_EQ(a.download<float>(), first);

  std::printf("%s, %ux%u:\n", caseName(c).c_str(), width, height);
  expectMatches("lightmap A", planes(first, pixels), vectors.at("lightmap_a").toFloat());
  std::vector<float> expectedB = vectors.at("lightmap_b").toFloat();
  if (!c.emission) {  // B's 4th component, the emissive: PyTorch's holds glow, the lightmap none
    const auto emissive = expectedB.begin() + 3 * std::ptrdiff_t(pixels);
    EXPECT_GT(*std::max_element(emissive, emissive + std::ptrdiff_t(pixels)), 1e-3f);
    std::fill(emissive, emissive + std::ptrdiff_t(pixels), 0.0f);
  }
  const std::vector<float> actualB = planes(b.download<float>(), pixels);
  expectMatches("lightmap B", actualB, expectedB);
  if (!c.emission) {
    EXPECT_EQ(*std::max_element(actualB.begin() + 3 * std::ptrdiff_t(pixels), actualB.end()), 0.0f);
  }
  for (const io::Tensor& tensor : vectors.tensors)
    if (tensor.name.starts_with("node.")) {
      const std::string node = tensor.name.substr(5);
      if (const nn::FeatureMap* map = network.featureMap(node))  // none: a block with its head fused
        expectMatches(node, map->download(), tensor.toFloat());
    }
}

INSTANTIATE_TEST_SUITE_P(
    Vectors, NetworkParity,
    ::testing::Values(ParityCase{"default"}, ParityCase{"tiny"}, ParityCase{"tiny", Precision::Fp32, false},
                      ParityCase{"fine_alpha"}, ParityCase{"emission_guide"},
                      ParityCase{"emission_passthrough"}, ParityCase{"albedo_input"}, ParityCase{"half_stem"},
                      ParityCase{"naf_wide"},
                      ParityCase{"default", Precision::Fp32, true, nn::Tiling::Pixels},
                      ParityCase{"naf_wide", Precision::Fp32, true, nn::Tiling::Pixels},
                      // Skipped where the device has no cooperative matrices (lavapipe).
                      ParityCase{"default", Precision::Fp16, true, nn::Tiling::Matrix},
                      ParityCase{"naf_wide", Precision::Fp16, true, nn::Tiling::Matrix},
                      ParityCase{"albedo_input", Precision::Fp16, true, nn::Tiling::Matrix},
                      ParityCase{"emission_guide", Precision::Fp32, true, nn::Tiling::Device, false}),
    [](const ::testing::TestParamInfo<ParityCase>& info) { return caseName(info.param); });
// Label "long" (tests/nn/CMakeLists.txt): about a minute of pipeline compilation on a cold shader cache.
INSTANTIATE_TEST_SUITE_P(LONG_Vectors, NetworkParity,
                         ::testing::Values(ParityCase{"default", Precision::Fp16},
                                           ParityCase{"tiny", Precision::Fp16}),
                         [](const ::testing::TestParamInfo<ParityCase>& info) {
                           return caseName(info.param);
                         });

}  // namespace
}  // namespace sixway::test
