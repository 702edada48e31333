#include "io/exr.h"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfVersion.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <fstream>

#include "io/error.h"
#include "io/file_access.h"

namespace sixway::io {

namespace {

constexpr int kRowsPerBlock = 64;

// OpenEXR's messages may span lines; ours are one line.
std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

bool hasExrMagic(const std::filesystem::path& path) {
  char magic[4] = {};
  std::ifstream in(path, std::ios::binary);
  in.read(magic, sizeof(magic));
  return in && Imf::isImfMagic(magic);
}

// A header string (name or type): NUL-terminated, at most 255 bytes (OpenEXR's long names); "" at the end of
// a header or past the end of the file.
std::string headerString(std::ifstream& in) {
  std::string text;
  for (char c; in.get(c) && c != '\0';) {
    if (text.size() == 255) return text;  // too long: the size check below fails on what follows
    text += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  }
  return text;
}

// OpenEXR allocates the size an attribute states before it reads the value: a corrupt 1.5 KB header stating
// 1.6 GB took seconds and that memory. So each attribute must fit in what is left of the file. Layout: magic,
// version (bit 12: multi-part), then per header (name\0 type\0 int32 size, value) up to an empty name; a
// multi-part file's list of headers ends with an empty header.
void requireAttributesFitTheFile(const std::filesystem::path& path) {
  const std::string source = path.string();
  std::error_code error;
  const uint64_t fileSize = std::filesystem::file_size(path, error);
  if (error) throw InputError(source, "cannot read: " + error.message());
  std::ifstream in(path, std::ios::binary);
  char version[4] = {};
  in.seekg(4);
  in.read(version, sizeof(version));
  const bool multiPart = (static_cast<unsigned char>(version[1]) & 0x10) != 0;
  for (;;) {
    int attributes = 0;
    for (std::string name = headerString(in); !name.empty(); name = headerString(in), ++attributes) {
      headerString(in);  // the type
      unsigned char bytes[4] = {};
      in.read(reinterpret_cast<char*>(bytes), sizeof(bytes));
      if (!in) throw InputError(source, "truncated OpenEXR header (in attribute '" + name + "')");
      const int64_t size = int32_t(uint32_t(bytes[0]) | uint32_t(bytes[1]) << 8 | uint32_t(bytes[2]) << 16 |
                                   uint32_t(bytes[3]) << 24);
      const uint64_t left = fileSize - uint64_t(in.tellg());
      if (size < 0 || uint64_t(size) > left)
        throw InputError(source, "corrupt OpenEXR header: attribute '" + name + "' states " +
                                     std::to_string(size) + " bytes, more than the " + std::to_string(left) +
                                     " left in the file");
      in.seekg(size, std::ios::cur);
    }
    if (!multiPart || attributes == 0) return;
  }
}

std::string channelList(const Imf::ChannelList& channels) {
  std::string list;
  for (auto it = channels.begin(); it != channels.end(); ++it)
    list += (list.empty() ? "" : ", ") + std::string(it.name());
  return list;
}

}  // namespace

void writeExr(const std::filesystem::path& path, const Image& image, ExrPixelType pixelType,
              const ExrAttributes& attributes) {
  const std::string source = path.string();
  requireConsistentImage(source, image);
  for (std::size_t c = 0; c < image.channels.size(); ++c) {
    const bool repeated = std::find(image.channels.begin(), image.channels.begin() + c, image.channels[c]) !=
                          image.channels.begin() + c;
    if (image.channels[c].empty() || repeated) {
      throw InputError(source, "channel name '" + image.channels[c] + "' is empty or repeated");
    }
  }

  const Imf::PixelType type = pixelType == ExrPixelType::Half ? Imf::HALF : Imf::FLOAT;
  const std::size_t channelCount = image.channels.size();
  const std::size_t elementSize = type == Imf::HALF ? sizeof(Imath::half) : sizeof(float);
  // OpenEXR does not convert on output, so half channels need half values in memory. Values past the largest
  // half (65504) saturate there instead of becoming inf.
  std::vector<Imath::half> halves;
  if (type == Imf::HALF) {
    const float largest = HALF_MAX;
    halves.reserve(image.pixels.size());
    for (const float v : image.pixels) halves.emplace_back(std::clamp(v, -largest, largest));
  }
  const char* base = type == Imf::HALF ? reinterpret_cast<const char*>(halves.data())
                                       : reinterpret_cast<const char*>(image.pixels.data());

  AtomicFile file(path);
  try {
    Imf::Header header(image.width, image.height);
    Imf::FrameBuffer frameBuffer;
    for (std::size_t c = 0; c < channelCount; ++c) {
      header.channels().insert(image.channels[c], Imf::Channel(type));
      // Slice takes a non-const pointer for both directions; OutputFile only reads through it.
      frameBuffer.insert(image.channels[c],
                         Imf::Slice(type, const_cast<char*>(base) + c * elementSize,
                                    channelCount * elementSize, channelCount * elementSize * image.width));
    }
    // OpenEXR refuses (throws) a string under the name of one of its own attributes of another type.
    for (const auto& [name, value] : attributes) {
      header.insert(name, Imf::StringAttribute(value));
    }
    Imf::OutputFile out(file.temporaryPath().c_str(), header);
    out.setFrameBuffer(frameBuffer);
    out.writePixels(image.height);
  } catch (const std::exception& error) {
    throw InputError(source, "cannot write OpenEXR: " + oneLine(error.what()));
  }
  file.commit();
}

ExrImage readExr(const std::filesystem::path& path, const std::vector<std::string>& channels) {
  const std::string source = path.string();
  requireRegularFile(path);
  if (!hasExrMagic(path)) throw InputError(source, "not an OpenEXR file (no OpenEXR magic number)");
  requireAttributesFitTheFile(path);

  ExrImage result;
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imf::ChannelList& fileChannels = header.channels();

    std::vector<std::string> names = channels;
    if (names.empty()) {
      for (auto it = fileChannels.begin(); it != fileChannels.end(); ++it) names.emplace_back(it.name());
    }
    for (const std::string& name : names) {
      const Imf::Channel* channel = fileChannels.findChannel(name);
      if (!channel) {
        throw InputError(source,
                         "no channel '" + name + "' (the file has: " + channelList(fileChannels) + ")");
      }
      if (channel->xSampling != 1 || channel->ySampling != 1) {
        throw InputError(source, "channel '" + name + "' is subsampled, which is not supported");
      }
    }

    const Imath::Box2i dataWindow = header.dataWindow();
    const int64_t width = int64_t(dataWindow.max.x) - dataWindow.min.x + 1;
    const int64_t height = int64_t(dataWindow.max.y) - dataWindow.min.y + 1;
    if (width < 1 || height < 1) throw InputError(source, "empty data window");
    requireReadableSize(source, width, height);
    Image& image = result.image;
    image.width = static_cast<int>(width);
    image.height = static_cast<int>(height);
    image.channels = names;
    // The image grows by blocks of rows as they are read: a header may claim any size up to the limit, but
    // memory goes only to rows the file holds (a truncated or corrupt file fails at its first bad block).
    const std::size_t xStride = names.size() * sizeof(float);
    const std::size_t yStride = xStride * image.width;
    for (int row = 0; row < image.height; row += kRowsPerBlock) {
      const int rows = std::min(kRowsPerBlock, image.height - row);
      image.pixels.resize((static_cast<std::size_t>(row) + rows) * image.width * names.size());
      Imf::FrameBuffer frameBuffer;
      for (std::size_t c = 0; c < names.size(); ++c) {
        frameBuffer.insert(
            names[c], Imf::Slice::Make(Imf::FLOAT, image.pixels.data() + c, dataWindow, xStride, yStride));
      }
      file.setFrameBuffer(frameBuffer);
      file.readPixels(dataWindow.min.y + row, dataWindow.min.y + row + rows - 1);
    }

    for (auto it = header.begin(); it != header.end(); ++it) {
      if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) {
        result.attributes[it.name()] = text->value();
      }
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& error) {
    throw InputError(source, "cannot read OpenEXR (truncated or corrupt?): " + oneLine(error.what()));
  }
  return result;
}

}  // namespace sixway::io
