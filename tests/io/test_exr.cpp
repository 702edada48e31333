#include "io/exr.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "support/input_error.h"
#include "support/temp_dir.h"

namespace sixway::io {
namespace {

namespace fs = std::filesystem;
using test::inputErrorMessage;
using test::namesFileAndProblem;
using ::testing::ElementsAre;

const std::vector<std::string> kChannels = {"R", "G", "B", "A", "emissive", "lightmapA.R"};

// Values that are not round in binary, spread over several orders of magnitude, different in every channel.
Image noisyImage(int width, int height, const std::vector<std::string>& channels) {
  Image image(width, height, channels);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    image.pixels[i] =
        std::sin(0.37f * static_cast<float>(i)) * std::pow(10.0f, static_cast<float>(i % 5) - 2.0f);
  }
  return image;
}

// `read` has the same channels as `written` (maybe in another order) with values within `tolerance(value)`.
template <typename Tolerance>
void expectSameChannels(const Image& read, const Image& written, Tolerance tolerance) {
  ASSERT_EQ(read.width, written.width);
  ASSERT_EQ(read.height, written.height);
  ASSERT_EQ(read.channels.size(), written.channels.size());
  for (int c = 0; c < written.channelCount(); ++c) {
    const std::optional<int> readChannel = read.channelIndex(written.channels[c]);
    ASSERT_TRUE(readChannel) << written.channels[c];
    for (int y = 0; y < written.height; ++y) {
      for (int x = 0; x < written.width; ++x) {
        const float value = written.at(x, y, c);
        ASSERT_NEAR(read.at(x, y, *readChannel), value, tolerance(value))
            << written.channels[c] << " " << x << "," << y;
      }
    }
  }
}

class ExrTest : public ::testing::Test {
 protected:
  test::TempDir dir;
  fs::path file = dir / "image.exr";
};

TEST_F(ExrTest, FloatRoundTripIsExactWithAttributes) {
  const Image image = noisyImage(13, 7, kChannels);
  writeExr(file, image, ExrPixelType::Float, {{"colorspace", "linear"}, {"sixway.packing", "unity-six-way"}});
  const ExrImage read = readExr(file);
  expectSameChannels(read.image, image, [](float) { return 0.0f; });
  EXPECT_EQ(read.attributes.at("colorspace"), "linear");
  EXPECT_EQ(read.attributes.at("sixway.packing"), "unity-six-way");
}

TEST_F(ExrTest, HalfRoundTripIsWithinHalfPrecision) {
  const Image image = noisyImage(13, 7, kChannels);
  writeExr(file, image);
  // Half keeps 11 significant bits: relative rounding error up to 2^-11 (values here are far from subnormal).
  expectSameChannels(readExr(file).image, image,
                     [](float value) { return std::abs(value) * 0x1p-11f + 1e-7f; });
}

TEST_F(ExrTest, AllChannelsComeInTheFileOrderWhichIsSortedByName) {
  writeExr(file, noisyImage(2, 2, kChannels));
  EXPECT_THAT(readExr(file).image.channels, ElementsAre("A", "B", "G", "R", "emissive", "lightmapA.R"));
}

TEST_F(ExrTest, ReadsRequestedChannelsInTheRequestedOrder) {
  const Image image = noisyImage(5, 3, kChannels);
  writeExr(file, image, ExrPixelType::Float);
  const Image read = readExr(file, {"lightmapA.R", "R"}).image;
  EXPECT_THAT(read.channels, ElementsAre("lightmapA.R", "R"));
  EXPECT_EQ(read.at(4, 2, 0), image.at(4, 2, 5));
  EXPECT_EQ(read.at(4, 2, 1), image.at(4, 2, 0));
}

TEST_F(ExrTest, ReadsTheDataWindow) {
  // Written by OpenEXR directly: a 4x2 data window at (10, 20) inside a 64x64 display window.
  const Imath::Box2i display({0, 0}, {63, 63}), data({10, 20}, {13, 21});
  Imf::Header header(display, data);
  header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
  std::vector<float> values = {0, 1, 2, 3, 4, 5, 6, 7};
  Imf::FrameBuffer frameBuffer;
  frameBuffer.insert("Y", Imf::Slice::Make(Imf::FLOAT, values.data(), data));
  {
    Imf::OutputFile out(file.c_str(), header);
    out.setFrameBuffer(frameBuffer);
    out.writePixels(2);
  }
  const Image read = readExr(file).image;
  EXPECT_EQ(read.width, 4);
  EXPECT_EQ(read.height, 2);
  EXPECT_EQ(read.pixels, values);
}

// Bad input: each case names the file and the problem.

TEST_F(ExrTest, MissingFile) {
  EXPECT_THAT(inputErrorMessage([&] { readExr(file); }), namesFileAndProblem(file, "no such file"));
}

TEST_F(ExrTest, TextFileNamedExr) {
  std::ofstream(file) << "colour: linear\n";
  EXPECT_THAT(inputErrorMessage([&] { readExr(file); }), namesFileAndProblem(file, "not an OpenEXR file"));
}

TEST_F(ExrTest, TruncatedFile) {
  writeExr(file, noisyImage(64, 64, {"R", "G", "B"}), ExrPixelType::Float);
  fs::resize_file(file, fs::file_size(file) / 2);
  EXPECT_THAT(inputErrorMessage([&] { readExr(file); }), namesFileAndProblem(file, "cannot read OpenEXR"));
}

TEST_F(ExrTest, MissingChannel) {
  writeExr(file, noisyImage(2, 2, {"R", "G"}));
  EXPECT_THAT(inputErrorMessage([&] {
                readExr(file, {"R", "emissive"});
              }),
              namesFileAndProblem(file, "no channel 'emissive' (the file has: G, R)"));
}

TEST_F(ExrTest, WriteIntoAMissingDirectory) {
  const fs::path target = dir / "missing" / "image.exr";
  EXPECT_THAT(inputErrorMessage([&] { writeExr(target, noisyImage(1, 1, {"Y"})); }),
              namesFileAndProblem(target, "does not exist"));
}

TEST_F(ExrTest, WriteRepeatedChannelName) {
  EXPECT_THAT(inputErrorMessage([&] {
                writeExr(file, noisyImage(1, 1, {"Y", "Y"}));
              }),
              namesFileAndProblem(file, "channel name 'Y' is empty or repeated"));
}

TEST_F(ExrTest, WriteAttributeThatOpenExrReservesForAnotherType) {
  EXPECT_THAT(inputErrorMessage([&] {
                writeExr(file, noisyImage(1, 1, {"Y"}), ExrPixelType::Half, {{"compression", "zip"}});
              }),
              namesFileAndProblem(file,
                                  "cannot write OpenEXR: Cannot assign a value of type \"string\" to image "
                                  "attribute \"compression\""));
  EXPECT_FALSE(fs::exists(file));
}

}  // namespace
}  // namespace sixway::io
