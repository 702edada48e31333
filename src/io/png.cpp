#include "io/png.h"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <memory>

#include "io/byte_encoding.h"
#include "io/error.h"
#include "io/file_access.h"

namespace sixway::io {

namespace {

constexpr std::array<unsigned char, 8> kPngSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};

bool hasPngSignature(const std::filesystem::path& path) {
  std::array<unsigned char, 8> head{};
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(head.data()), head.size());
  return in && head == kPngSignature;
}

// Debian's stb_image grows its buffer to a chunk's stated length before it reads the chunk, so a 128-byte
// file whose IDAT claims 1.3 GB allocated 2 GiB (found by fuzzing). Every chunk (length, type, data, CRC: PNG
// spec §5.3) must lie inside the file; the signature is already checked.
void requireChunksInsideFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  const uint64_t size = std::filesystem::file_size(path);
  uint64_t at = kPngSignature.size();
  std::array<unsigned char, 8> head{};
  while (at + head.size() <= size &&
         in.seekg(std::streamoff(at)).read(reinterpret_cast<char*>(head.data()), 8)) {
    const uint64_t length = uint64_t(head[0]) << 24 | head[1] << 16 | head[2] << 8 | head[3];
    const std::string type(head.begin() + 4, head.end());
    if (at + 12 + length > size)
      throw InputError(path.string(), "corrupt or truncated PNG file (chunk " + type + " of " +
                                          std::to_string(length) + " bytes at byte " + std::to_string(at) +
                                          " runs past the end of the file, " + std::to_string(size) +
                                          " bytes)");
    if (type == "IEND") return;
    at += 12 + length;
  }
}

std::vector<std::string> channelNames(int count) {
  switch (count) {
    case 1:
      return {"Y"};
    case 2:
      return {"Y", "A"};
    case 3:
      return {"R", "G", "B"};
    default:
      return {"R", "G", "B", "A"};
  }
}

}  // namespace

void writePng(const std::filesystem::path& path, const Image& image, ByteEncoding encoding) {
  const std::string source = path.string();
  requireConsistentImage(source, image);
  const int channels = image.channelCount();
  if (channels > 4) {
    throw InputError(source, "PNG holds 1 to 4 channels, the image has " + std::to_string(channels));
  }
  const std::vector<uint8_t> bytes = toBytes(image, encoding);

  // Encoded in memory, then written with every write checked (stb does not report a full disk).
  std::vector<uint8_t> encoded;
  if (!stbi_write_png_to_func(appendBytes, &encoded, image.width, image.height, channels, bytes.data(),
                              image.width * channels)) {
    throw InputError(source, "cannot encode the PNG file");
  }
  AtomicFile file(path);
  file.writeAll(encoded);
  file.commit();
}

Image readPng(const std::filesystem::path& path) {
  const std::string source = path.string();
  requireRegularFile(path);
  if (!hasPngSignature(path)) throw InputError(source, "not a PNG file (no PNG signature)");
  requireChunksInsideFile(path);

  int width = 0, height = 0, channels = 0;
  // stb accepts sides up to 2^24 and allocates the whole image before it decodes a row.
  if (stbi_info(path.c_str(), &width, &height, &channels)) requireReadableSize(source, width, height);
  const std::unique_ptr<stbi_uc, void (*)(void*)> bytes(
      stbi_load(path.c_str(), &width, &height, &channels, 0), stbi_image_free);
  if (!bytes) {
    throw InputError(source, std::string("corrupt or truncated PNG file (") + stbi_failure_reason() + ")");
  }

  Image image(width, height, channelNames(channels));
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = bytes.get()[i] / 255.0f;
  return image;
}

}  // namespace sixway::io
