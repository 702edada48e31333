#pragma once
// 8-bit PNG images, for people to look at (numbers go to EXR).
#include <filesystem>

#include "io/byte_encoding.h"
#include "io/image.h"

namespace sixway::io {

// Writes 1 (grey), 2 (grey, alpha), 3 (RGB) or 4 (RGBA) channels, sRGB-encoded by default (for display); the
// channel names are not stored.
// Throws InputError naming the file for an empty image, more than 4 channels, or a failed write.
void writePng(const std::filesystem::path& path, const Image& image,
              ByteEncoding encoding = ByteEncoding::SRGB);

// The 8-bit codes divided by 255, with no transfer function undone. Channels are named "Y" / "Y","A" /
// "R","G","B" / "R","G","B","A"; 16-bit files are reduced to 8 bits. Throws InputError naming the file.
Image readPng(const std::filesystem::path& path);

}  // namespace sixway::io
