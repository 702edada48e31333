#include "io/tga.h"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <memory>
#include <vector>

#include "io/byte_encoding.h"
#include "io/error.h"
#include "io/file_access.h"

namespace sixway::io {

void writeTga(const std::filesystem::path& path, const Image& image, ByteEncoding encoding) {
  const std::string source = path.string();
  requireConsistentImage(source, image);
  const int channels = image.channelCount();
  if (channels > 4)
    throw InputError(source, "TGA holds 1 to 4 channels, the image has " + std::to_string(channels));
  const std::vector<uint8_t> bytes = toBytes(image, encoding);
  // Encoded in memory, then written with every write checked (stb does not report a full disk).
  std::vector<uint8_t> encoded;
  if (!stbi_write_tga_to_func(appendBytes, &encoded, image.width, image.height, channels, bytes.data()))
    throw InputError(source, "cannot encode the TGA file");
  AtomicFile file(path);
  file.writeAll(encoded);
  file.commit();
}

namespace {

// stb_image reads the bytes a truncated TGA lacks as zeros, so a 34-byte file could decode to a 16384² image.
// The header (TGA 2.0 spec, "Image Specification") tells the least the pixel data can take: every pixel for a
// raw image; for run-length encoding, one packet (a count byte and one pixel) per 128 pixels at best.
void requirePixelDataPresent(const std::filesystem::path& path, int64_t width, int64_t height) {
  std::array<uint8_t, 18> header{};
  std::ifstream in(path, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(header.data()), header.size()))
    throw InputError(path.string(), "not a readable TGA file (the 18-byte header is cut short)");
  const auto word = [&](int at) { return header[at] | header[at + 1] << 8; };
  const int64_t idLength = header[0];
  const int64_t colorMapBytes = header[1] ? word(5) * int64_t((header[7] + 7) / 8) : 0;
  const int64_t pixelBytes = (header[16] + 7) / 8;
  const bool runLength = header[2] >= 9;
  const int64_t pixels = width * height;
  const int64_t least = runLength ? (pixels + 127) / 128 * (1 + pixelBytes) : pixels * pixelBytes;
  const int64_t held = int64_t(std::filesystem::file_size(path)) - 18 - idLength - colorMapBytes;
  if (held < least)
    throw InputError(path.string(), "not a readable TGA file (" + std::to_string(width) + "x" +
                                        std::to_string(height) + " pixels need at least " +
                                        std::to_string(least) + " bytes of pixel data, the file holds " +
                                        std::to_string(std::max<int64_t>(held, 0)) + ")");
}

}  // namespace

Image readTga(const std::filesystem::path& path) {
  const std::string source = path.string();
  requireRegularFile(path);
  int width = 0, height = 0, channels = 0;
  // stb accepts sides up to 2^24 and allocates the whole image before it decodes a row.
  if (stbi_info(path.c_str(), &width, &height, &channels)) {
    requireReadableSize(source, width, height);
    requirePixelDataPresent(path, width, height);
  }
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
