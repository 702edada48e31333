#pragma once
// How linear values become the 8-bit codes of PNG and TGA files.
#include <cstdint>
#include <vector>

#include "io/image.h"

namespace sixway::io {

// SRGB applies the sRGB transfer function to the colour channels and leaves alpha (the last channel of a grey
// + alpha or RGBA image) linear; Linear stores the values as they are. Both clip to [0, 1] (NaN becomes 0)
// and round to nearest.
enum class ByteEncoding { SRGB, Linear };

// The image's pixels as 8-bit codes, interleaved as they are.
std::vector<uint8_t> toBytes(const Image& image, ByteEncoding encoding);

}  // namespace sixway::io
