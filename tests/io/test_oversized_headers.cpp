// Image headers that claim far more pixels than the file holds, found by fuzzing (tests/fuzz/,
// docs/robustness.md "Fuzzing"): refused by size before anything is allocated, or read without spending
// memory on rows the file does not have. The inputs are in tests/data/fuzz/.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <filesystem>

#include "io/exr.h"
#include "io/png.h"
#include "io/tga.h"
#include "support/input_error.h"

namespace sixway::io {
namespace {

using test::inputErrorMessage;
using test::namesFileAndProblem;

const std::filesystem::path kData = std::filesystem::path(SIXWAY_TEST_DATA_DIR) / "fuzz";

// The process's peak resident memory so far, in MiB (each test runs in its own process under CTest).
double peakResidentMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

TEST(OversizedHeaderTest, ExrDataWindowWiderThanTheLimit) {
  // guide.exr with its data window made 100000 pixels wide.
  const auto file = kData / "exr_wide_data_window.exr";
  EXPECT_THAT(inputErrorMessage([&] { readExr(file); }),
              namesFileAndProblem(file, "image of 100000x32 pixels, more than 16384 per side"));
}

TEST(OversizedHeaderTest, ExrAttributeLargerThanTheFileIsRefusedBeforeOpenExrAllocatesIt) {
  // A 1,497-byte header whose first attribute states 1,634,231,040 bytes: OpenEXR allocates and clears that
  // much before it reads (2 s alone, 13 s under load with AddressSanitizer).
  const auto file = kData / "exr_attribute_states_1634231040_bytes.exr";
  EXPECT_THAT(inputErrorMessage([&] { readExr(file); }),
              namesFileAndProblem(file,
                                  "corrupt OpenEXR header: attribute 'channelv/1?\?' states 1634231040 "
                                  "bytes, more than the 1471 left in the file"));
  EXPECT_LT(peakResidentMiB(), 200.0);
}

TEST(OversizedHeaderTest, ExrClaimingMoreRowsThanItHoldsFailsWithoutAllocatingThem) {
  // guide.exr (32×32, ZIP, 3 channels) with its data window made 8192×8192: reading it whole would first take
  // 8192² × 3 floats (768 MiB); block by block it fails at the first block the file does not hold.
  const auto file = kData / "exr_claims_8192.exr";
  const double before = peakResidentMiB();
  EXPECT_THAT(inputErrorMessage([&] { readExr(file); }), namesFileAndProblem(file, "cannot read OpenEXR"));
  EXPECT_LT(peakResidentMiB() - before, 100.0);
}

TEST(OversizedHeaderTest, PngWiderThanTheLimit) {
  // stb_image refuses PNGs over 1 GiB itself, but not a side beyond the limit the other readers keep.
  const auto file = kData / "png_20000x10_no_data.png";
  EXPECT_THAT(inputErrorMessage([&] { readPng(file); }),
              namesFileAndProblem(file, "image of 20000x10 pixels, more than 16384 per side"));
}

TEST(OversizedHeaderTest, PngChunkLongerThanTheFile) {
  // 128 bytes whose second IDAT chunk states 1,300,824,138 bytes: stb_image grew its buffer to 2 GiB for it.
  const auto file = kData / "png_idat_claims_1300824138_bytes.png";
  const double before = peakResidentMiB();
  EXPECT_THAT(inputErrorMessage([&] { readPng(file); }),
              namesFileAndProblem(file,
                                  "chunk IDAT of 1300824138 bytes at byte 71 runs past the end of the file, "
                                  "128 bytes"));
  EXPECT_LT(peakResidentMiB() - before, 100.0);
}

TEST(OversizedHeaderTest, TgaClaimingTwentyThousandSquare) {
  // A 34-byte TGA: stb_image reads missing bytes as zeros, so it would return a 20000² RGBA image (1.5 GiB,
  // 6 GiB as floats) from nothing.
  const auto file = kData / "tga_20000x20000_no_data.tga";
  const double before = peakResidentMiB();
  EXPECT_THAT(inputErrorMessage([&] { readTga(file); }),
              namesFileAndProblem(file, "image of 20000x20000 pixels, more than 16384 per side"));
  EXPECT_LT(peakResidentMiB() - before, 100.0);
}

TEST(OversizedHeaderTest, TgaClaimingMorePixelsThanItHolds) {
  // Within the side limit, but 34 bytes cannot hold 16000² RGBA pixels (1 GiB, 4 GiB as floats, were stb
  // left to fill the rest with zeros).
  const auto file = kData / "tga_16000x16000_no_data.tga";
  const double before = peakResidentMiB();
  EXPECT_THAT(inputErrorMessage([&] { readTga(file); }),
              namesFileAndProblem(file,
                                  "16000x16000 pixels need at least 1024000000 bytes of pixel data, "
                                  "the file holds 16"));
  EXPECT_LT(peakResidentMiB() - before, 100.0);
}

}  // namespace
}  // namespace sixway::io
