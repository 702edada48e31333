#include "io/image.h"

#include "io/error.h"

namespace sixway::io {

void requireReadableSize(std::string_view source, int64_t width, int64_t height) {
  if (width > kMaxImageSide || height > kMaxImageSide) {
    throw InputError(source, "image of " + std::to_string(width) + "x" + std::to_string(height) +
                                 " pixels, more than " + std::to_string(kMaxImageSide) +
                                 " per side (corrupt, or too large to read)");
  }
}

void requireConsistentImage(std::string_view source, const Image& image) {
  if (image.width <= 0 || image.height <= 0) {
    throw InputError(source, "image size " + std::to_string(image.width) + "x" +
                                 std::to_string(image.height) + " is empty");
  }
  if (image.channels.empty()) throw InputError(source, "image has no channels");
  const std::size_t expected = static_cast<std::size_t>(image.width) * image.height * image.channels.size();
  if (image.pixels.size() != expected) {
    throw InputError(source, "image has " + std::to_string(image.pixels.size()) + " values, " +
                                 std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
                                 std::to_string(image.channels.size()) + " needs " +
                                 std::to_string(expected));
  }
}

}  // namespace sixway::io
