#pragma once
// A float image with named channels, shared by the PNG and EXR code.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sixway::io {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::string> channels;
  std::vector<float> pixels;  // interleaved, row-major, row 0 at the top

  Image() = default;
  // A zero-filled image.
  Image(int width, int height, std::vector<std::string> channels)
      : width(width),
        height(height),
        channels(std::move(channels)),
        pixels(static_cast<std::size_t>(width) * height * this->channels.size(), 0.0f) {}

  int channelCount() const { return static_cast<int>(channels.size()); }
  std::size_t index(int x, int y, int c) const {
    return (static_cast<std::size_t>(y) * width + x) * channels.size() + c;
  }
  float& at(int x, int y, int c) { return pixels[index(x, y, c)]; }
  float at(int x, int y, int c) const { return pixels[index(x, y, c)]; }

  std::optional<int> channelIndex(std::string_view name) const {
    for (std::size_t c = 0; c < channels.size(); ++c) {
      if (channels[c] == name) return static_cast<int>(c);
    }
    return std::nullopt;
  }
};

// The largest image side read from a file: the largest texture game engines take, as for flipbooks
// (reference::kMaxFlipbookSide). An RGBA float image of that size is already 4 GiB.
inline constexpr int kMaxImageSide = 16384;
// Throws InputError naming `source` when a file's header claims an image wider or taller than kMaxImageSide,
// before anything is allocated for it.
void requireReadableSize(std::string_view source, int64_t width, int64_t height);

// Throws InputError naming `source` unless the image has a positive size, at least one channel and
// width * height * channels pixel values.
void requireConsistentImage(std::string_view source, const Image& image);

}  // namespace sixway::io
