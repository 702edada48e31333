#pragma once
// Image comparison for tests: PSNR (docs/conventions.md, "Metrics": linear values clipped to [0, 1],
// 10·log10(1/MSE)), max-abs and per-channel figures. On failure the actual, expected and difference images
// are written next to the test log (build/tests/artifacts/<suite>.<test>/) so a person can look.
#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "io/image.h"

namespace sixway::test {

struct ImageDifference {
  double mse = 0;                   // over all channels, clipped values
  double psnr = 0;                  // +inf when identical
  double maxAbs = 0;                // unclipped
  std::vector<double> channelPsnr;  // per channel
  std::vector<double> channelMaxAbs;
  int worstX = 0, worstY = 0, worstChannel = 0;  // where maxAbs is
};

// Throws std::invalid_argument when the sizes or channel counts differ.
ImageDifference compareImages(const io::Image& actual, const io::Image& expected);

struct ImageTolerance {
  double maxAbs = std::numeric_limits<double>::infinity();
  double minPsnr = 0;
};

// Passes when both bounds hold; otherwise says by how much, and writes the images.
::testing::AssertionResult imagesMatch(const io::Image& actual, const io::Image& expected,
                                       const ImageTolerance& tolerance, const std::string& label);

// Where the current test's failure images go.
std::filesystem::path testArtifactDir();

}  // namespace sixway::test
