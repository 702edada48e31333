#include "io/png.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>

#include "support/input_error.h"
#include "support/temp_dir.h"

namespace sixway::io {
namespace {

namespace fs = std::filesystem;
using test::inputErrorMessage;
using test::namesFileAndProblem;
using ::testing::ElementsAre;

// A small image whose values sweep [0, 1] differently per channel.
Image gradient(int width, int height, std::vector<std::string> channels) {
  Image image(width, height, std::move(channels));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < image.channelCount(); ++c) {
        image.at(x, y, c) = static_cast<float>((x + 3 * y + 7 * c) % 256) / 255.0f;
      }
    }
  }
  return image;
}

class PngTest : public ::testing::Test {
 protected:
  test::TempDir dir;
  fs::path file = dir / "image.png";
};

TEST_F(PngTest, LinearRoundTripIsExactForByteValues) {
  const Image image = gradient(17, 5, {"R", "G", "B", "A"});
  writePng(file, image, ByteEncoding::Linear);
  const Image read = readPng(file);
  EXPECT_EQ(read.width, 17);
  EXPECT_EQ(read.height, 5);
  EXPECT_THAT(read.channels, ElementsAre("R", "G", "B", "A"));
  ASSERT_EQ(read.pixels.size(), image.pixels.size());
  for (std::size_t i = 0; i < image.pixels.size(); ++i) EXPECT_FLOAT_EQ(read.pixels[i], image.pixels[i]) << i;
}

TEST_F(PngTest, RowZeroIsTheTopRow) {
  Image image(1, 2, {"Y"});
  image.at(0, 0, 0) = 1.0f;
  writePng(file, image, ByteEncoding::Linear);
  const Image read = readPng(file);
  EXPECT_EQ(read.at(0, 0, 0), 1.0f);
  EXPECT_EQ(read.at(0, 1, 0), 0.0f);
}

TEST_F(PngTest, SrgbEncodesColourButNotAlpha) {
  Image image(1, 1, {"R", "G", "B", "A"});
  image.pixels = {0.5f, 0.0f, 1.0f, 0.5f};
  writePng(file, image);
  // sRGB(0.5) = 0.7354 -> 188; alpha 0.5 stays linear -> 128.
  EXPECT_THAT(readPng(file).pixels, ElementsAre(188 / 255.0f, 0.0f, 1.0f, 128 / 255.0f));
}

TEST_F(PngTest, ClipsOutOfRangeValuesAndNaN) {
  Image image(4, 1, {"Y"});
  image.pixels = {-1.0f, 2.0f, std::numeric_limits<float>::quiet_NaN(),
                  std::numeric_limits<float>::infinity()};
  writePng(file, image, ByteEncoding::Linear);
  EXPECT_THAT(readPng(file).pixels, ElementsAre(0.0f, 1.0f, 0.0f, 1.0f));
}

TEST_F(PngTest, GreyAndGreyAlphaAndRgb) {
  const std::vector<std::vector<std::string>> layouts = {{"Y"}, {"Y", "A"}, {"R", "G", "B"}};
  for (const auto& channels : layouts) {
    writePng(file, gradient(3, 2, channels), ByteEncoding::Linear);
    EXPECT_EQ(readPng(file).channels, channels);
  }
}

// Bad input: each case names the file and the problem.

TEST_F(PngTest, MissingFile) {
  EXPECT_THAT(inputErrorMessage([&] { readPng(file); }), namesFileAndProblem(file, "no such file"));
}

TEST_F(PngTest, TextFileNamedPng) {
  std::ofstream(file) << "this is not an image\n";
  EXPECT_THAT(inputErrorMessage([&] { readPng(file); }), namesFileAndProblem(file, "not a PNG file"));
}

TEST_F(PngTest, TruncatedFile) {
  writePng(file, gradient(64, 64, {"R", "G", "B"}), ByteEncoding::Linear);
  fs::resize_file(file, fs::file_size(file) / 2);
  EXPECT_THAT(inputErrorMessage([&] { readPng(file); }),
              namesFileAndProblem(file, "corrupt or truncated PNG file"));
}

TEST_F(PngTest, WriteZeroSizeImage) {
  EXPECT_THAT(inputErrorMessage([&] { writePng(file, Image(0, 4, {"Y"})); }),
              namesFileAndProblem(file, "image size 0x4 is empty"));
}

TEST_F(PngTest, WriteFiveChannels) {
  EXPECT_THAT(inputErrorMessage([&] {
                writePng(file, Image(2, 2, {"R", "G", "B", "A", "Z"}));
              }),
              namesFileAndProblem(file, "PNG holds 1 to 4 channels, the image has 5"));
}

TEST_F(PngTest, WritePixelCountThatDoesNotMatchTheSize) {
  Image image(2, 2, {"Y"});
  image.pixels.pop_back();
  EXPECT_THAT(inputErrorMessage([&] { writePng(file, image); }),
              namesFileAndProblem(file, "image has 3 values"));
}

TEST_F(PngTest, WriteIntoAMissingDirectory) {
  const fs::path target = dir / "missing" / "image.png";
  EXPECT_THAT(inputErrorMessage([&] { writePng(target, Image(1, 1, {"Y"})); }),
              namesFileAndProblem(target, "does not exist"));
}

}  // namespace
}  // namespace sixway::io
