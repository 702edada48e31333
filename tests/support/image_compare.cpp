#include "support/image_compare.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "io/exr.h"
#include "io/png.h"

namespace sixway::test {
namespace {

double psnrOf(double mse) {
  return mse == 0 ? std::numeric_limits<double>::infinity() : 10 * std::log10(1 / mse);
}

double clip01(float v) {
  return std::isnan(v) ? 0.0 : std::clamp(double(v), 0.0, 1.0);
}

// |actual − expected|, scaled so the largest difference is white.
io::Image differenceImage(const io::Image& actual, const io::Image& expected, double maxAbs) {
  io::Image diff(actual.width, actual.height, actual.channels);
  const double scale = maxAbs > 0 ? 1 / maxAbs : 1;
  for (size_t i = 0; i < diff.pixels.size(); ++i)
    diff.pixels[i] = float(std::fabs(double(actual.pixels[i]) - expected.pixels[i]) * scale);
  return diff;
}

}  // namespace

ImageDifference compareImages(const io::Image& actual, const io::Image& expected) {
  if (actual.width != expected.width || actual.height != expected.height ||
      actual.channelCount() != expected.channelCount())
    throw std::invalid_argument(
        "images differ in shape: " + std::to_string(actual.width) + "x" + std::to_string(actual.height) +
        "x" + std::to_string(actual.channelCount()) + " vs " + std::to_string(expected.width) + "x" +
        std::to_string(expected.height) + "x" + std::to_string(expected.channelCount()));
  const int channels = actual.channelCount();
  std::vector<double> squared(channels, 0.0);
  ImageDifference d;
  d.channelMaxAbs.assign(channels, 0.0);
  d.maxAbs = -1;
  for (int y = 0; y < actual.height; ++y)
    for (int x = 0; x < actual.width; ++x)
      for (int c = 0; c < channels; ++c) {
        const float a = actual.at(x, y, c), e = expected.at(x, y, c);
        const double clipped = clip01(a) - clip01(e);
        squared[c] += clipped * clipped;
        // A NaN anywhere is the worst possible difference.
        const double abs = (std::isnan(a) != std::isnan(e))
                               ? std::numeric_limits<double>::infinity()
                               : (std::isnan(a) ? 0.0 : std::fabs(double(a) - e));
        d.channelMaxAbs[c] = std::max(d.channelMaxAbs[c], abs);
        if (abs > d.maxAbs) {
          d.maxAbs = abs;
          d.worstX = x, d.worstY = y, d.worstChannel = c;
        }
      }
  const double pixels = double(actual.width) * actual.height;
  double total = 0;
  for (int c = 0; c < channels; ++c) {
    d.channelPsnr.push_back(psnrOf(squared[c] / pixels));
    total += squared[c];
  }
  d.mse = total / (pixels * channels);
  d.psnr = psnrOf(d.mse);
  return d;
}

std::filesystem::path testArtifactDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "no-test";
  std::replace(name.begin(), name.end(), '/', '_');
  return std::filesystem::path(SIXWAY_TEST_ARTIFACT_DIR) / name;
}

::testing::AssertionResult imagesMatch(const io::Image& actual, const io::Image& expected,
                                       const ImageTolerance& tolerance, const std::string& label) {
  ImageDifference d;
  try {
    d = compareImages(actual, expected);
  } catch (const std::invalid_argument& e) {
    return ::testing::AssertionFailure() << label << ": " << e.what();
  }
  if (d.maxAbs <= tolerance.maxAbs && d.psnr >= tolerance.minPsnr) return ::testing::AssertionSuccess();

  std::ostringstream message;
  message << label << ": PSNR " << d.psnr << " dB (need >= " << tolerance.minPsnr << "), max |diff| "
          << d.maxAbs << " (allowed " << tolerance.maxAbs << ") at x=" << d.worstX << " y=" << d.worstY
          << " channel " << actual.channels[d.worstChannel] << " (actual "
          << actual.at(d.worstX, d.worstY, d.worstChannel) << ", expected "
          << expected.at(d.worstX, d.worstY, d.worstChannel) << "); per channel:";
  for (size_t c = 0; c < d.channelPsnr.size(); ++c)
    message << " " << actual.channels[c] << " " << d.channelPsnr[c] << " dB/" << d.channelMaxAbs[c];
  const std::filesystem::path dir = testArtifactDir();
  try {
    std::filesystem::create_directories(dir);
    for (auto& [suffix, image] : {std::pair{"actual", &actual}, std::pair{"expected", &expected}}) {
      io::writeExr(dir / (label + "-" + suffix + ".exr"), *image, io::ExrPixelType::Float);
      if (image->channelCount() <= 4) io::writePng(dir / (label + "-" + suffix + ".png"), *image);
    }
    io::Image diff = differenceImage(actual, expected, d.maxAbs);
    if (diff.channelCount() <= 4) io::writePng(dir / (label + "-diff.png"), diff, io::ByteEncoding::Linear);
    message << "\nimages written to " << dir.string() << " (diff scaled by 1/" << d.maxAbs << ")";
  } catch (const std::exception& e) {
    message << "\n(could not write the images: " << e.what() << ")";
  }
  return ::testing::AssertionFailure() << message.str();
}

}  // namespace sixway::test
