#pragma once
// OpenEXR images (for numbers): any named channels, half or float, with string attributes.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "io/image.h"

namespace sixway::io {

enum class ExrPixelType { Half, Float };

using ExrAttributes = std::map<std::string, std::string>;  // e.g. {"colorspace", "linear"}

// Writes every channel of `image` as `pixelType` (ZIP compressed, lossless), with `attributes` as string
// attributes. Throws InputError naming the file when the image is inconsistent, an attribute name is one
// OpenEXR reserves for another type, or the file cannot be written.
void writeExr(const std::filesystem::path& path, const Image& image,
              ExrPixelType pixelType = ExrPixelType::Half, const ExrAttributes& attributes = {});

struct ExrImage {
  Image image;               // the data window, converted to float
  ExrAttributes attributes;  // the file's string attributes
};

// Reads the `channels` named, in that order, or every channel (in the file's order, which OpenEXR sorts by
// name) when `channels` is empty. Throws InputError naming the file for a missing file, a file that is not
// OpenEXR, a truncated or corrupt file, or a missing channel.
ExrImage readExr(const std::filesystem::path& path, const std::vector<std::string>& channels = {});

}  // namespace sixway::io
