#include "eval/eval_strip.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "io/png.h"

namespace sixway::eval {
namespace {

constexpr int kGap = 2;  // background pixels between panels

// IEC 61966-2-1: linear → sRGB-encoded, so the strip can mix display-encoded frames and false colours in one
// linear-stored PNG.
float srgbEncoded(float v) {
  v = std::clamp(std::isnan(v) ? 0.0f : v, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

// Black → red → yellow → white (a "hot" ramp), display-encoded, for t in [0, 1].
std::array<float, 3> hot(float t) {
  t = std::clamp(std::isnan(t) ? 1.0f : t, 0.0f, 1.0f);
  return {std::clamp(3.0f * t, 0.0f, 1.0f), std::clamp(3.0f * t - 1.0f, 0.0f, 1.0f),
          std::clamp(3.0f * t - 2.0f, 0.0f, 1.0f)};
}

}  // namespace

std::vector<std::string> writeEvalStrip(const std::filesystem::path& path, const io::Image& truth,
                                        const std::vector<StripPanel>& methods, float errorGain,
                                        int minHeight) {
  const int w = truth.width, h = truth.height;
  const int scale = std::max(1, (minHeight + h - 1) / h);
  const int panels = 1 + 2 * int(methods.size());
  io::Image strip(panels * w * scale + (panels - 1) * kGap, h * scale, {"R", "G", "B"});
  std::fill(strip.pixels.begin(), strip.pixels.end(), 1.0f);
  std::vector<std::string> names{"truth"};

  const auto paint = [&](int panel, auto&& colourAt) {
    for (int y = 0; y < h * scale; ++y)
      for (int x = 0; x < w * scale; ++x) {
        const std::array<float, 3> c = colourAt(x / scale, y / scale);
        for (int k = 0; k < 3; ++k) strip.at(panel * (w * scale + kGap) + x, y, k) = c[k];
      }
  };
  const auto frame = [&](const io::Image& image) {
    return [&image](int x, int y) {
      return std::array<float, 3>{srgbEncoded(image.at(x, y, 0)), srgbEncoded(image.at(x, y, 1)),
                                  srgbEncoded(image.at(x, y, 2))};
    };
  };
  paint(0, frame(truth));
  for (size_t m = 0; m < methods.size(); ++m) {
    paint(1 + int(m), frame(*methods[m].image));
    names.push_back(methods[m].name);
  }
  for (size_t m = 0; m < methods.size(); ++m) {
    const io::Image& image = *methods[m].image;
    paint(1 + int(methods.size() + m), [&](int x, int y) {
      float error = 0.0f;
      for (int c = 0; c < 3; ++c)
        error +=
            std::abs(std::clamp(image.at(x, y, c), 0.0f, 1.0f) - std::clamp(truth.at(x, y, c), 0.0f, 1.0f));
      return hot(errorGain * error / 3.0f);
    });
    names.push_back("|" + methods[m].name + " - truth| x" + std::to_string(int(errorGain)));
  }
  io::writePng(path, strip, io::ByteEncoding::Linear);
  return names;
}

}  // namespace sixway::eval
