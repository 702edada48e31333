// The image comparison used by every golden-image test.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "support/image_compare.h"

namespace sixway::test {
namespace {

io::Image constant(float value, int channels = 3) {
  io::Image image(
      8, 4,
      channels == 3 ? std::vector<std::string>{"R", "G", "B"} : std::vector<std::string>{"R", "G", "B", "A"});
  std::fill(image.pixels.begin(), image.pixels.end(), value);
  return image;
}

TEST(ImageCompare, IdenticalImagesHaveInfinitePsnr) {
  ImageDifference d = compareImages(constant(0.3f), constant(0.3f));
  EXPECT_TRUE(std::isinf(d.psnr));
  EXPECT_EQ(d.maxAbs, 0.0);
}

TEST(ImageCompare, UniformOffsetGivesTheAnalyticPsnr) {
  // MSE = 0.1² = 0.01 → PSNR = 10·log10(100) = 20 dB.
  ImageDifference d = compareImages(constant(0.5f), constant(0.4f));
  EXPECT_NEAR(d.mse, 0.01, 1e-7);
  EXPECT_NEAR(d.psnr, 20.0, 1e-4);
  EXPECT_NEAR(d.maxAbs, 0.1, 1e-6);
}

TEST(ImageCompare, ValuesAreClippedForPsnrButNotForMaxAbs) {
  ImageDifference d = compareImages(constant(3.0f), constant(1.0f));
  EXPECT_TRUE(std::isinf(d.psnr));  // both clip to 1
  EXPECT_NEAR(d.maxAbs, 2.0, 1e-6);
}

TEST(ImageCompare, LocatesTheWorstPixelAndChannel) {
  io::Image a = constant(0.5f), b = constant(0.5f);
  a.at(5, 2, 1) = 0.9f;
  ImageDifference d = compareImages(a, b);
  EXPECT_EQ(d.worstX, 5);
  EXPECT_EQ(d.worstY, 2);
  EXPECT_EQ(d.worstChannel, 1);
  EXPECT_TRUE(std::isinf(d.channelPsnr[0]));
  EXPECT_FALSE(std::isinf(d.channelPsnr[1]));
}

TEST(ImageCompare, NanIsTheWorstDifference) {
  io::Image a = constant(0.5f);
  a.at(0, 0, 0) = std::nanf("");
  EXPECT_TRUE(std::isinf(compareImages(a, constant(0.5f)).maxAbs));
}

TEST(ImageCompare, FailureExplainsAndWritesTheImages) {
  io::Image a = constant(0.5f, 4), b = constant(0.25f, 4);
  ::testing::AssertionResult result = imagesMatch(a, b, {0.1, 30}, "frame");
  ASSERT_FALSE(result);
  EXPECT_THAT(result.message(), ::testing::HasSubstr("max |diff| 0.25"));
  for (const char* file : {"frame-actual.png", "frame-expected.png", "frame-diff.png", "frame-actual.exr"})
    EXPECT_TRUE(std::filesystem::exists(testArtifactDir() / file)) << file;
  std::filesystem::remove_all(testArtifactDir());
}

TEST(ImageCompare, ShapeMismatchFailsWithoutThrowing) {
  io::Image a = constant(0.5f, 3), b = constant(0.5f, 4);
  ::testing::AssertionResult result = imagesMatch(a, b, {}, "x");
  EXPECT_FALSE(result);
  EXPECT_THAT(result.message(), ::testing::HasSubstr("differ in shape"));
}

}  // namespace
}  // namespace sixway::test
