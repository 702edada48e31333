// The graphics path: pipeline with specialization and push constants, dynamic rendering,
// viewport orientation (+y up, row 0 at the top) and premultiplied "over" blending.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "gpu/check.h"
#include "gpu/gpu_spec.h"
#include "gpu/image.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "support/gpu_fixture.h"

namespace sixway::test {
namespace {

struct FillPush {
  float clipMin[2], clipMax[2], targetSize[2], alpha, pad;
};

class GraphicsTest : public GpuTest {
 protected:
  static constexpr uint32_t kSize = 32;
  static constexpr float kBlue = 0.75f;

  std::vector<float> draw(gpu::Blend blend, FillPush push, std::array<float, 4> clear,
                          std::optional<VkRect2D> area = std::nullopt) {
    gpu::GraphicsPipelineDesc desc;
    desc.vertexShader = "gpu/fill_gradient.vert";
    desc.fragmentShader = "gpu/fill_gradient.frag";
    desc.pushConstantBytes = sizeof(FillPush);
    desc.spec.set(gpu::spec::kBlue, kBlue);
    desc.colorFormats = {VK_FORMAT_R32G32B32A32_SFLOAT};
    desc.blend = blend;
    gpu::Pipeline pipeline(context(), pipelineCache(), desc);
    gpu::Image target(context(), {kSize, kSize, 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                                  VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "target"});
    gpu::Sequence sequence(context());
    gpu::Draw quad{&pipeline, {}, gpu::pushBytes(push), nullptr, nullptr, 6};
    quad.area = area;
    sequence.render({{&target}, nullptr, clear, std::nullopt}, std::span(&quad, 1));
    sequence.submit();
    return target.download<float>();
  }
};

TEST_F(GraphicsTest, UpperHalfOfClipSpaceIsTheTopRowsOfTheImage) {
  FillPush push{{-1, 0}, {1, 1}, {kSize, kSize}, 1.0f, 0};
  std::vector<float> image = draw(gpu::Blend::None, push, {0, 0, 0, 0});
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      const float* p = &image[(y * kSize + x) * 4];
      if (y < kSize / 2) {  // covered: the colour is the pixel centre over the size
        EXPECT_NEAR(p[0], (x + 0.5f) / kSize, 1e-6) << x << "," << y;
        EXPECT_NEAR(p[1], (y + 0.5f) / kSize, 1e-6) << x << "," << y;
        EXPECT_EQ(p[2], kBlue);
        EXPECT_EQ(p[3], 1.0f);
      } else {
        EXPECT_EQ(p[0] + p[1] + p[2] + p[3], 0.0f) << x << "," << y;
      }
    }
}

TEST_F(GraphicsTest, DrawAreaHoldsTheClipSquareUpperHalfOnTop) {
  // The upper half of clip space drawn into a 16 x 8 area at (8, 4): rows 4..7 of columns 8..23 only.
  const VkRect2D area{{8, 4}, {16, 8}};
  FillPush push{{-1, 0}, {1, 1}, {kSize, kSize}, 1.0f, 0};
  std::vector<float> image = draw(gpu::Blend::None, push, {0, 0, 0, 0}, area);
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      const float* p = &image[(y * kSize + x) * 4];
      if (x >= 8 && x < 24 && y >= 4 && y < 8) {  // fragment coordinates stay those of the whole target
        EXPECT_NEAR(p[0], (x + 0.5f) / kSize, 1e-6) << x << "," << y;
        EXPECT_NEAR(p[1], (y + 0.5f) / kSize, 1e-6) << x << "," << y;
        EXPECT_EQ(p[3], 1.0f);
      } else {
        EXPECT_EQ(p[0] + p[1] + p[2] + p[3], 0.0f) << x << "," << y;
      }
    }
}

TEST_F(GraphicsTest, DrawAreaOutsideTheTargetsIsRefused) {
  FillPush push{{-1, -1}, {1, 1}, {kSize, kSize}, 1.0f, 0};
  EXPECT_THROW(draw(gpu::Blend::None, push, {0, 0, 0, 0}, VkRect2D{{20, 0}, {16, 8}}), gpu::GpuError);
}

TEST_F(GraphicsTest, PremultipliedOverBlendsAsDesignSays) {
  const float alpha = 0.4f;
  const std::array<float, 4> background = {0.2f, 0.5f, 0.9f, 1.0f};
  FillPush push{{-1, -1}, {1, 1}, {kSize, kSize}, alpha, 0};
  std::vector<float> image = draw(gpu::Blend::PremultipliedOver, push, background);
  for (uint32_t y = 0; y < kSize; y += 5)
    for (uint32_t x = 0; x < kSize; x += 3) {
      const float source[4] = {alpha * (x + 0.5f) / kSize, alpha * (y + 0.5f) / kSize, alpha * kBlue, alpha};
      for (int c = 0; c < 4; ++c)  // out = src + (1 − src.a) · dst
        EXPECT_NEAR(image[(y * kSize + x) * 4 + c], source[c] + (1 - alpha) * background[c], 1e-6);
    }
}

}  // namespace
}  // namespace sixway::test
