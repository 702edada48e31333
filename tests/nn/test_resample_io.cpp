// Bilinear upsampling, the input kernel (guide image into the first feature map, padded) and the output
// kernel (head maps decoded and packed into the two lightmaps, cropped) against CPU references.
#include <array>
#include <cmath>
#include <utility>

#include "gpu/buffer.h"
#include "gpu/check.h"
#include "gpu/image.h"
#include "gpu/sequence.h"
#include "io/safetensors.h"
#include "nn/io_kernels.h"
#include "nn/nn_test_support.h"
#include "nn/upsample_kernel.h"

namespace sixway::test {
namespace {

using nn::Precision;

class ResampleIoTest : public NnTest, public ::testing::WithParamInterface<Precision> {
 protected:
  double tolerance() const { return GetParam() == Precision::Fp16 ? kFp16Tolerance : kFp32Tolerance; }
};

std::vector<std::byte> texelBytes(const std::vector<float>& rgba, VkFormat format) {
  if (format == VK_FORMAT_R32G32B32A32_SFLOAT) {
    auto bytes = std::as_bytes(std::span(rgba));
    return {bytes.begin(), bytes.end()};
  }
  const io::Tensor half = io::Tensor::fromFloat("", io::DType::F16, {int64_t(rgba.size())}, rgba);
  auto bytes = std::as_bytes(std::span(half.bytes));
  return {bytes.begin(), bytes.end()};
}

std::vector<float> texelFloats(const gpu::Image& image) {
  if (image.desc().format == VK_FORMAT_R32G32B32A32_SFLOAT) return image.download<float>();
  io::Tensor half{"", io::DType::F16, {int64_t(image.byteSize() / 2)}, image.download<uint8_t>()};
  return half.toFloat();
}

TEST_P(ResampleIoTest, UpsampleBilinearMatchesCpu) {
  std::mt19937 rng(3);
  for (int factor : {2, 3}) {
    const CpuMap input = randomMap(5, 7, 9, rng);
    const CpuMap expected = upsampleBilinear(input, factor);
    nn::UpsampleKernel kernel(setup(GetParam()), {9, 7, 5}, factor);
    const nn::FeatureMap in = upload(input, GetParam());
    nn::FeatureMap out = empty(kernel.output(), GetParam());
    gpu::Sequence sequence(context());
    kernel.record(sequence, in, out);
    sequence.submit();
    EXPECT_TRUE(allClose(out.download(), expected.values, tolerance(), tolerance())) << "factor " << factor;
  }
}

// A buffer of one float, as nn::Network holds the encoded albedo.
gpu::Buffer sceneBuffer(const gpu::Context& context, float encodedAlbedo) {
  gpu::Buffer buffer(context, sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                     gpu::MemoryKind::FrameParameters, "scene");
  buffer.upload(std::as_bytes(std::span(&encodedAlbedo, 1)));
  return buffer;
}

// 3 guide channels into a map of 4; 5 into a map of 8, the 5th from the emission image's R channel; with the
// albedo, the channel after the guide's holds it at every pixel of the map, the padding too.
TEST_P(ResampleIoTest, InputCopiesTheGuideChannelsAndZeroPads) {
  const uint32_t guideWidth = 13, guideHeight = 9, mapWidth = 16, mapHeight = 12;
  const size_t pixels = size_t(guideWidth) * guideHeight;
  const float encodedAlbedo = -0.625f;
  const gpu::Buffer scene = sceneBuffer(context(), encodedAlbedo);
  std::mt19937 rng(4);
  for (VkFormat format : {VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT})
    for (auto [guideChannels, albedoChannel] : {std::pair{3, -1}, {5, -1}, {3, 3}, {5, 5}}) {
      const VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT;
      std::vector<float> rgba = randomValues(pixels * 4, rng, 0.0f, 1.0f);
      gpu::Image guide(context(), {guideWidth, guideHeight, 1, format, usage, "guide"});
      guide.upload(texelBytes(rgba, format));
      rgba = texelFloats(guide);  // as stored (rounded to half for RGBA16F)
      const std::vector<float> emitted = randomValues(pixels, rng, 0.0f, 2.0f);
      gpu::Image emission(context(), {guideWidth, guideHeight, 1, VK_FORMAT_R32_SFLOAT, usage, "emission"});
      emission.upload(std::as_bytes(std::span(emitted)));
      const uint32_t mapChannels = guideChannels > 4 ? 8 : 4;
      nn::InputKernel kernel(setup(GetParam()), {mapWidth, mapHeight, mapChannels}, guideWidth, guideHeight,
                             guideChannels, albedoChannel);
      nn::FeatureMap map = empty({mapWidth, mapHeight, mapChannels}, GetParam());
      gpu::Sequence sequence(context());
      kernel.record(sequence, guide, guideChannels > 4 ? &emission : nullptr, scene, map);
      sequence.submit();
      CpuMap expected(int(mapChannels), mapHeight, mapWidth);
      for (uint32_t y = 0; y < guideHeight; ++y)
        for (uint32_t x = 0; x < guideWidth; ++x) {
          for (int c = 0; c < std::min(guideChannels, 4); ++c)
            expected.at(c, y, x) = rgba[(y * guideWidth + x) * 4 + c];
          if (guideChannels > 4) expected.at(4, y, x) = emitted[y * guideWidth + x];
        }
      if (albedoChannel >= 0)
        for (uint32_t y = 0; y < mapHeight; ++y)
          for (uint32_t x = 0; x < mapWidth; ++x) expected.at(albedoChannel, y, x) = encodedAlbedo;
      EXPECT_TRUE(allClose(map.download(), expected.values, tolerance(), tolerance()))
          << "format " << format << ", " << guideChannels << " channels, albedo channel " << albedoChannel;
    }
}

// A 5-channel guide needs its emission image: a clear error, not an unbound descriptor.
TEST_P(ResampleIoTest, InputOfFiveChannelsRefusesAMissingEmission) {
  nn::InputKernel kernel(setup(GetParam()), {16, 16, 8}, 16, 16, 5, -1);
  gpu::Image guide(context(),
                   {16, 16, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT, "guide"});
  nn::FeatureMap map = empty({16, 16, 8}, GetParam());
  gpu::Sequence sequence(context());
  EXPECT_THROW(kernel.record(sequence, guide, nullptr, sceneBuffer(context(), 0.0f), map), gpu::GpuError);
}

TEST_P(ResampleIoTest, OutputDecodesPacksAndCrops) {
  const uint32_t mapWidth = 16, mapHeight = 12, width = 13, height = 9;
  std::mt19937 rng(5);
  // Four heads of two channels in adapter order: (left, right), (top, bottom), (front, back), (alpha,
  // emissive).
  nn::Node node;
  node.channels = {"left", "right", "top", "bottom", "front", "back", "alpha", "emissive"};
  node.encodings.assign(8, nn::Encoding::Srgb);
  node.encodings[6] = nn::Encoding::Linear;
  node.lightmapA = {1, 2, 5, 6};
  node.lightmapB = {0, 3, 4, 7};
  std::vector<CpuMap> heads;
  std::vector<nn::FeatureMap> maps;
  for (int h = 0; h < 4; ++h) {
    heads.push_back(randomMap(2, mapHeight, mapWidth, rng));
    for (float& v : heads.back().values) v = v * 0.7f + 0.2f;  // both sides of 0 and of sRGB's knee 0.04045
    maps.push_back(upload(heads.back(), GetParam()));
  }
  for (VkFormat format : {VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT}) {
    nn::OutputKernel kernel(setup(GetParam()), nn::outputLayout(node, {2, 2, 2, 2}), {mapWidth, mapHeight, 2},
                            width, height);
    const gpu::ImageDesc desc{
        width, height, 1, format, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "A"};
    gpu::Image a(context(), desc), b(context(), desc);
    gpu::Sequence sequence(context());
    kernel.record(sequence, {&maps[0], &maps[1], &maps[2], &maps[3]}, a, b);
    sequence.submit();
    std::vector<float> expectedA, expectedB;
    for (uint32_t y = 0; y < height; ++y)
      for (uint32_t x = 0; x < width; ++x) {
        std::array<float, 8> channel;
        for (int k = 0; k < 8; ++k) {
          const float raw = heads[k / 2].at(k % 2, y, x);
          channel[k] = std::max(k == 6 ? raw : srgbToLinear(raw), 0.0f);
        }
        for (int i : node.lightmapA) expectedA.push_back(channel[i]);
        for (int i : node.lightmapB) expectedB.push_back(channel[i]);
      }
    const double t = std::max(tolerance(), format == VK_FORMAT_R16G16B16A16_SFLOAT ? kFp16Tolerance : 0.0);
    EXPECT_TRUE(allClose(texelFloats(a), expectedA, t, t)) << "format " << format;
    EXPECT_TRUE(allClose(texelFloats(b), expectedB, t, t)) << "format " << format;
  }
}

INSTANTIATE_TEST_SUITE_P(Precisions, ResampleIoTest, ::testing::Values(Precision::Fp32, Precision::Fp16),
                         [](const ::testing::TestParamInfo<Precision>& info) {
                           return info.param == Precision::Fp16 ? "Fp16" : "Fp32";
                         });

}  // namespace
}  // namespace sixway::test
