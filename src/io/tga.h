#pragma once
// 8-bit TGA images (run-length encoded), the format some engines' texture pipelines still expect for
// flipbooks. Values are stored as they are (linear) unless sRGB encoding is asked for.
#include <filesystem>

#include "io/byte_encoding.h"
#include "io/image.h"

namespace sixway::io {

// Writes 1 (grey), 2 (grey, alpha), 3 (RGB) or 4 (RGBA) channels, clipped to [0, 1] (NaN → 0) and rounded to
// 8 bits. Throws InputError naming the file for an empty image, more than 4 channels, or a failed write.
void writeTga(const std::filesystem::path& path, const Image& image,
              ByteEncoding encoding = ByteEncoding::Linear);

// The 8-bit codes divided by 255; channels named as by readPng. Throws InputError naming the file when it is
// missing or not a readable TGA file.
Image readTga(const std::filesystem::path& path);

}  // namespace sixway::io
