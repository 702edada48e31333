#include "io/tga.h"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "io/error.h"
#include "io/file_access.h"

namespace sixway::io {

void writeTga(const std::filesystem::path& path, const Image& image) {
  const std::string source = path.string();
  requireConsistentImage(source, image);
  const int channels = image.channelCount();
  if (channels > 4)
    throw InputError(source, "TGA holds 1 to 4 channels, the image has " + std::to_string(channels));
  std::vector<uint8_t> bytes(image.pixels.size());
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    const float v = image.pixels[i] > 0.0f ? std::min(image.pixels[i], 1.0f) : 0.0f;  // NaN → 0
    bytes[i] = static_cast<uint8_t>(std::lround(v * 255.0f));
  }
  AtomicFile file(path);
  if (!stbi_write_tga(file.temporaryPath().c_str(), image.width, image.height, channels, bytes.data()))
    throw InputError(source, "cannot write the TGA file");
  file.commit();
}

Image readTga(const std::filesystem::path& path) {
  const std::string source = path.string();
  requireRegularFile(path);
  int width = 0, height = 0, channels = 0;
  // stb accepts sides up to 2^24 and allocates the whole image before it decodes a row.
  if (stbi_info(path.c_str(), &width, &height, &channels)) requireReadableSize(source, width, height);
  const std::unique_ptr<stbi_uc, void (*)(void*)> bytes(
      stbi_load(path.c_str(), &width, &height, &channels, 0), stbi_image_free);
  if (!bytes)
    throw InputError(source, std::string("not a readable TGA file (") + stbi_failure_reason() + ")");
  static const std::vector<std::string> names[4] = {{"Y"}, {"Y", "A"}, {"R", "G", "B"}, {"R", "G", "B", "A"}};
  Image image(width, height, names[channels - 1]);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = bytes.get()[i] / 255.0f;
  return image;
}

}  // namespace sixway::io
