#include "io/tga.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "support/input_error.h"
#include "support/temp_dir.h"

namespace sixway::io {
namespace {

using test::inputErrorMessage;
using test::namesFileAndProblem;

class TgaTest : public ::testing::Test {
 protected:
  test::TempDir dir;
  std::filesystem::path file = dir / "image.tga";
};

TEST_F(TgaTest, RoundTripsEightBitRgbaWithoutATransferFunction) {
  Image image(5, 3, {"R", "G", "B", "A"});
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x)
      for (int c = 0; c < 4; ++c) image.at(x, y, c) = float((x * 40 + y * 17 + c * 61) % 256) / 255.0f;
  writeTga(file, image);
  const Image back = readTga(file);
  ASSERT_EQ(back.width, 5);
  ASSERT_EQ(back.height, 3);
  ASSERT_EQ(back.channels, image.channels);
  for (size_t i = 0; i < image.pixels.size(); ++i) EXPECT_FLOAT_EQ(back.pixels[i], image.pixels[i]) << i;
}

TEST_F(TgaTest, ClipsAndRoundsToEightBits) {
  Image image(3, 1, {"Y"});
  image.pixels = {-0.5f, 0.5f, 7.0f};
  writeTga(file, image);
  EXPECT_EQ(readTga(file).pixels, (std::vector<float>{0.0f, 128 / 255.0f, 1.0f}));
}

TEST_F(TgaTest, BadInputNamesTheFile) {
  EXPECT_THAT(inputErrorMessage([&] {
                writeTga(file, Image(2, 2, {"a", "b", "c", "d", "e"}));
              }),
              namesFileAndProblem(file, "1 to 4 channels"));
  EXPECT_THAT(inputErrorMessage([&] { readTga(dir / "missing.tga"); }),
              namesFileAndProblem(dir / "missing.tga", "no such file"));
  std::ofstream(file) << "not an image";
  EXPECT_THAT(inputErrorMessage([&] { readTga(file); }),
              namesFileAndProblem(file, "not a readable TGA file"));
}

}  // namespace
}  // namespace sixway::io
