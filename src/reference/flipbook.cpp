#include "reference/flipbook.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <span>
#include <stdexcept>

#include "io/error.h"
#include "io/exr.h"
#include "io/file_access.h"
#include "io/json_reader.h"
#include "io/json_text.h"
#include "io/png.h"
#include "io/tga.h"
#include "reference/unity_meta.h"

namespace sixway::reference {
namespace {

constexpr const char* kFormat = "sixway-flipbook";
constexpr const char* kComponents = "RGBA";
// Keys of the eight channels in a description, in channel order.
const std::array<std::string, render::kSixWayChannels>& channelKeys() {
  static const std::array<std::string, render::kSixWayChannels> keys = {
      "right", "left", "top", "bottom", "back", "front", "alpha", "emissive"};
  return keys;
}

// The pixel of frame `frame`'s tile at (x, y) in the flipbook texture.
std::size_t tilePixel(const FlipbookLayout& l, int frame, int x, int y) {
  const int column = frame % l.columns, row = frame / l.columns;
  return std::size_t(row * l.tileHeight + y) * std::size_t(l.columns * l.tileWidth) + column * l.tileWidth +
         x;
}

float srgbDecode(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

std::string reference(const ChannelPacking& packing, int channel) {
  const auto& slot = packing.slots[channel];
  return packing.textures[slot.texture] + "." + kComponents[slot.component];
}

ChannelPacking::Slot parseReference(const io::JsonReader& r, const std::string& key, const std::string& text,
                                    const std::vector<std::string>& textures) {
  const auto dot = text.rfind('.');
  const std::string texture = dot == std::string::npos ? "" : text.substr(0, dot);
  const std::string component = dot == std::string::npos ? "" : text.substr(dot + 1);
  const auto t = std::find(textures.begin(), textures.end(), texture);
  const char* c = component.size() == 1 ? std::strchr(kComponents, component[0]) : nullptr;
  if (t == textures.end() || !c || !*c)
    r.fail(key, "must be \"<texture>.<R|G|B|A>\" naming one of the textures (got \"" + text + "\")");
  return {int(t - textures.begin()), int(c - kComponents)};
}

// The file of one texture: a path, or an object of paths by format (EXR preferred, then PNG, then TGA).
std::filesystem::path textureFile(const io::JsonReader& r, const std::string& name,
                                  const nlohmann::json& value) {
  const std::string key = "textures." + name;
  if (value.is_string()) return value.get<std::string>();
  if (value.is_object()) {
    for (const char* format : {"exr", "png", "tga"})
      if (value.contains(format) && value[format].is_string()) return value[format].get<std::string>();
  }
  r.fail(key, "must be a file name or an object with \"exr\", \"png\" or \"tga\" file names");
}

io::Image readTexture(const std::filesystem::path& file, bool srgb) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
  if (extension == ".exr") return io::readExr(file).image;  // EXR is linear whatever the description says
  io::Image image;
  if (extension == ".png") {
    image = io::readPng(file);
  } else if (extension == ".tga") {
    image = io::readTga(file);
  } else {
    throw io::InputError(file.string(), "unknown texture format (expected .exr, .png or .tga)");
  }
  if (srgb) {
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
      if (image.channels[i % image.channels.size()] != "A") image.pixels[i] = srgbDecode(image.pixels[i]);
  }
  return image;
}

}  // namespace

FlipbookLayout flipbookLayout(int frames, int tileWidth, int tileHeight, int columns) {
  FlipbookLayout l;
  l.frames = std::max(frames, 1);
  l.columns = columns > 0 ? std::min(columns, l.frames) : int(std::ceil(std::sqrt(double(l.frames)) - 1e-9));
  l.rows = (l.frames + l.columns - 1) / l.columns;
  l.tileWidth = tileWidth;
  l.tileHeight = tileHeight;
  return l;
}

void requireFlipbookFits(const FlipbookLayout& layout, const std::string& source) {
  const int64_t width = int64_t(layout.columns) * layout.tileWidth;
  const int64_t height = int64_t(layout.rows) * layout.tileHeight;
  if (width > kMaxFlipbookSide || height > kMaxFlipbookSide)
    throw io::InputError(
        source, std::to_string(layout.frames) + " tiles of " + std::to_string(layout.tileWidth) + "x" +
                    std::to_string(layout.tileHeight) + " in " + std::to_string(layout.columns) +
                    " columns make a " + std::to_string(width) + "x" + std::to_string(height) +
                    " flipbook, more than " + std::to_string(kMaxFlipbookSide) +
                    " per side; reduce the frames or the tile size");
}

std::optional<EmissiveMask> unityEmissiveMask(const scene::Smoke& smoke) {
  const std::optional<float> straight = render::emissiveStraightScale(smoke);
  const std::vector<render::GradientKey> keys = render::emissiveGradientFromRamp(smoke.emission);
  if (!straight || keys.empty()) return std::nullopt;
  // The ramp gradient's keys sit at their own luminance, so the straight value e / (alpha · straight) is at
  // most the top key's: that is the mask's 1. The colours are scaled to at most 1 and the multiplier takes
  // the scale back, so multiplier · gradient(mask) = straight · ramp gradient(mask · top), SixWayShading's
  // emission.
  const float top = keys.back().position;
  float brightest = 0.0f;
  for (const render::GradientKey& k : keys)
    brightest = std::max({brightest, k.color.r, k.color.g, k.color.b});
  EmissiveMask mask{.luminanceScale = *straight * top, .gradient = {}, .multiplier = *straight * brightest};
  // Unity's gradient is constant before its first key; sixway's rises from black at 0.
  mask.gradient.push_back({0.0f, glm::vec3(0.0f)});
  for (const render::GradientKey& k : keys) mask.gradient.push_back({k.position / top, k.color / brightest});
  return mask;
}

std::vector<io::Image> packFlipbook(const std::vector<io::Image>& frames, const FlipbookLayout& layout,
                                    const ChannelPacking& packing) {
  std::vector<io::Image> textures(
      packing.textures.size(),
      io::Image(layout.columns * layout.tileWidth, layout.rows * layout.tileHeight, {"R", "G", "B", "A"}));
  for (int f = 0; f < int(frames.size()) && f < layout.frames; ++f) {
    const io::Image& tile = frames[f];
    if (tile.width != layout.tileWidth || tile.height != layout.tileHeight ||
        tile.channelCount() != render::kSixWayChannels)
      throw std::invalid_argument("packFlipbook: frame " + std::to_string(f) +
                                  " is not an eight-channel tile");
    for (int y = 0; y < layout.tileHeight; ++y)
      for (int x = 0; x < layout.tileWidth; ++x)
        for (int c = 0; c < render::kSixWayChannels; ++c) {
          const auto& slot = packing.slots[c];
          if (slot.texture < 0) continue;
          textures[slot.texture].pixels[tilePixel(layout, f, x, y) * 4 + slot.component] = tile.at(x, y, c);
        }
  }
  return textures;
}

std::vector<io::Image> unpackFlipbook(const std::vector<io::Image>& textures, const FlipbookLayout& layout,
                                      const ChannelPacking& packing) {
  const auto& names = render::sixWayChannelNames();
  std::vector<io::Image> frames(layout.frames,
                                io::Image(layout.tileWidth, layout.tileHeight, {names.begin(), names.end()}));
  for (int f = 0; f < layout.frames; ++f)
    for (int y = 0; y < layout.tileHeight; ++y)
      for (int x = 0; x < layout.tileWidth; ++x)
        for (int c = 0; c < render::kSixWayChannels; ++c) {
          const auto& slot = packing.slots[c];
          if (slot.texture < 0) continue;
          const io::Image& t = textures[slot.texture];
          frames[f].at(x, y, c) = t.pixels[tilePixel(layout, f, x, y) * t.channelCount() + slot.component];
        }
  return frames;
}

// The frames with their emissive channel e replaced by the mask e / (alpha · luminanceScale), clamped to [0,
// 1].
std::vector<io::Image> withEmissiveMask(std::vector<io::Image> frames, const EmissiveMask& mask) {
  for (io::Image& frame : frames)
    for (int y = 0; y < frame.height; ++y)
      for (int x = 0; x < frame.width; ++x) {
        const float alpha = frame.at(x, y, render::Alpha);
        float& emissive = frame.at(x, y, render::Emissive);
        emissive = alpha > 0.0f ? std::clamp(emissive / (alpha * mask.luminanceScale), 0.0f, 1.0f) : 0.0f;
      }
  return frames;
}

nlohmann::json describeEmissive(const std::optional<EmissiveMask>& mask) {
  if (!mask) return {{"encoding", "premultiplied"}};
  nlohmann::json gradient = nlohmann::json::array();
  for (const render::GradientKey& k : mask->gradient)
    gradient.push_back({{"position", k.position}, {"color", {k.color.r, k.color.g, k.color.b}}});
  return {{"encoding", "mask"},
          {"luminance_scale", mask->luminanceScale},
          {"unity",
           {{"emissive_mode", "Single Channel"},
            {"emissive_multiplier", mask->multiplier},
            {"emissive_gradient", gradient}}}};
}

// What the 8-bit files lose: texels of the colour channels above 1 are clipped there (emission, bright rims);
// the EXR keeps them.
nlohmann::json eightBitClipping(const std::vector<io::Image>& textures) {
  std::size_t clipped = 0, colour = 0;
  float largest = 0.0f;
  for (const io::Image& t : textures)
    for (std::size_t i = 0; i < t.pixels.size(); ++i) {
      if (i % 4 == 3) continue;
      ++colour;
      clipped += t.pixels[i] > 1.0f;
      largest = std::max(largest, t.pixels[i]);
    }
  return {{"clipped_fraction", colour ? double(clipped) / double(colour) : 0.0}, {"largest_value", largest}};
}

std::filesystem::path writeFlipbook(const std::filesystem::path& directory, const std::string& stem,
                                    const std::vector<io::Image>& frames, const FlipbookLayout& layout,
                                    const ChannelPacking& packing, const nlohmann::json& provenance,
                                    std::optional<Scattering> scattering,
                                    const std::optional<EmissiveMask>& emissiveMask) {
  const std::vector<io::Image> textures =
      packFlipbook(emissiveMask ? withEmissiveMask(frames, *emissiveMask) : frames, layout, packing);
  nlohmann::json files = nlohmann::json::object();
  for (std::size_t t = 0; t < textures.size(); ++t) {
    const std::string base = stem + "_" + packing.textures[t];
    io::writeExr(directory / (base + ".exr"), textures[t], io::ExrPixelType::Half,
                 {{"colorspace", "linear"}, {"sixway", "six-way lightmaps, premultiplied"}});
    // 8-bit: sRGB-encoded colour (alpha linear), so the dark lightmaps keep their levels; Unity decodes them
    // (sRGBTexture in the .meta), readFlipbook too (the sidecar's color_space).
    io::writePng(directory / (base + ".png"), textures[t], io::ByteEncoding::SRGB);
    io::writeTga(directory / (base + ".tga"), textures[t], io::ByteEncoding::SRGB);
    for (const char* extension : {".exr", ".png", ".tga"}) {
      const std::string file = base + extension;
      // The id is seeded by what the texture is: a re-bake of the same source keeps Unity's references.
      const std::string meta = unityTextureMeta({.guid = unityGuid(io::jsonText(provenance) + "/" + file),
                                                 .halfFloat = std::string_view(extension) == ".exr",
                                                 .srgb = std::string_view(extension) != ".exr",
                                                 .width = textures[t].width,
                                                 .height = textures[t].height,
                                                 .columns = layout.columns,
                                                 .rows = layout.rows});
      io::AtomicFile metaFile(directory / (file + ".meta"));
      metaFile.writeAll(std::span(reinterpret_cast<const uint8_t*>(meta.data()), meta.size()));
      metaFile.commit();
    }
    files[packing.textures[t]] = {{"exr", base + ".exr"}, {"png", base + ".png"}, {"tga", base + ".tga"}};
  }
  nlohmann::json channels = nlohmann::json::object();
  for (int c = 0; c < render::kSixWayChannels; ++c)
    if (packing.slots[c].texture >= 0) channels[channelKeys()[c]] = reference(packing, c);
  nlohmann::json sidecar = {
      {"format", kFormat},
      {"version", 1},
      {"layout",
       {{"columns", layout.columns},
        {"rows", layout.rows},
        {"frames", layout.frames},
        {"tile_width", layout.tileWidth},
        {"tile_height", layout.tileHeight}}},
      {"textures", files},
      {"channels", channels},
      {"color_space", "srgb"},  // of the 8-bit files' colour components; EXR and alpha are linear
      {"eight_bit", eightBitClipping(textures)},
      {"premultiplied", true},
      {"emissive", describeEmissive(emissiveMask)},
      {"normalisation",
       "radiance toward the camera under a white directional light of irradiance pi, black world "
       "(1 = a white Lambertian surface facing the light); alpha = 1 - view transmittance"},
      {"provenance", provenance},
  };
  if (scattering) sidecar["scattering"] = scatteringName(*scattering);
  const std::filesystem::path path = directory / (stem + ".json");
  const std::string text = io::jsonText(sidecar, 2) + '\n';
  io::AtomicFile file(path);
  file.writeAll(std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
  file.commit();
  return path;
}

Flipbook readFlipbook(const std::filesystem::path& description) {
  const std::string source = description.string();
  const std::vector<uint8_t> bytes = io::readFileBytes(description);
  const nlohmann::json json =
      io::parseJsonText(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), source);
  io::JsonReader r(json, "", source);
  if (const auto format = r.maybe<std::string>("format"); format && *format != kFormat)
    r.fail("format", std::string("must be \"") + kFormat + "\" (got \"" + *format + "\")");
  r.optional<int>("version", 1, io::inRange(1, 1));
  r.maybe<std::string>("normalisation");
  r.has("provenance");  // free-form: where the flipbook came from
  r.has("eight_bit");   // informational: what the 8-bit files clip

  Flipbook book;
  if (const auto scattering = r.maybe<std::string>("scattering"))
    book.scattering = r.pick<Scattering>(
        "scattering", *scattering, {{"single", Scattering::Single}, {"multiple", Scattering::Multiple}});
  FlipbookLayout& l = book.layout;
  r.object("layout", [&l](io::JsonReader& o) {
    l.columns = o.required<int>("columns", io::inRange(1, 4096));
    l.rows = o.required<int>("rows", io::inRange(1, 4096));
    l.tileWidth = o.required<int>("tile_width", io::inRange(1, 16384));
    l.tileHeight = o.required<int>("tile_height", io::inRange(1, 16384));
    l.frames = o.optional<int>("frames", l.columns * l.rows, io::inRange(1, l.columns * l.rows));
    return 0;
  });
  const bool srgb = r.optional<std::string>("color_space", "linear", [](const std::string& s) {
    return s == "linear" || s == "srgb" ? "" : "must be \"linear\" or \"srgb\" (got \"" + s + "\")";
  }) == "srgb";
  const bool premultiplied = r.optional<bool>("premultiplied", true);
  // A mask's luminance scale; none: the emissive component is premultiplied like the others (or, with
  // "premultiplied": false, straight like them).
  const std::optional<float> maskScale =
      r.optionalObject("emissive", [](io::JsonReader& o) {
         o.has("unity");  // informational: the settings for Unity's output
         const bool mask = o.choice<bool>("encoding", {{"mask", true}, {"premultiplied", false}});
         return mask ? std::optional(o.required<float>("luminance_scale", io::positive())) : std::nullopt;
       }).value_or(std::nullopt);

  if (!r.has("textures")) r.fail("textures", "required key missing");
  const nlohmann::json& texturesJson = json["textures"];
  if (!texturesJson.is_object() || texturesJson.empty())
    r.fail("textures", "must be an object naming the texture files");
  ChannelPacking packing;
  std::vector<io::Image> textures;
  for (const auto& [name, value] : texturesJson.items()) {
    packing.textures.push_back(name);
    const std::filesystem::path file = description.parent_path() / textureFile(r, name, value);
    io::Image image = readTexture(file, srgb);
    if (image.width != l.columns * l.tileWidth || image.height != l.rows * l.tileHeight)
      throw io::InputError(file.string(), "is " + std::to_string(image.width) + "x" +
                                              std::to_string(image.height) + ", the layout needs " +
                                              std::to_string(l.columns * l.tileWidth) + "x" +
                                              std::to_string(l.rows * l.tileHeight));
    // Components in R, G, B, A order, whatever order the file lists them in.
    io::Image rgba(image.width, image.height, {"R", "G", "B", "A"});
    for (int c = 0; c < 4; ++c) {
      const auto index = image.channelIndex(std::string(1, kComponents[c]));
      if (!index) continue;
      for (std::size_t i = 0; i < std::size_t(image.width) * image.height; ++i)
        rgba.pixels[i * 4 + c] = image.pixels[i * image.channelCount() + *index];
    }
    textures.push_back(std::move(rgba));
  }
  r.object("channels", [&](io::JsonReader& o) {
    for (int c = 0; c < render::kSixWayChannels; ++c) {
      const std::string& key = channelKeys()[c];
      const std::optional<std::string> text =
          c == render::Emissive ? o.maybe<std::string>(key) : std::optional(o.required<std::string>(key));
      if (text) packing.slots[c] = parseReference(o, key, *text, packing.textures);
    }
    return 0;
  });
  r.finish();

  book.frames = unpackFlipbook(textures, l, packing);
  for (io::Image& frame : book.frames)
    for (int y = 0; y < frame.height; ++y)
      for (int x = 0; x < frame.width; ++x) {
        const float alpha = frame.at(x, y, render::Alpha);
        for (int c = 0; c < render::kSixWayChannels; ++c) {
          if (c == render::Alpha) continue;
          if (c == render::Emissive && maskScale)
            frame.at(x, y, c) *= alpha * *maskScale;
          else if (!premultiplied)
            frame.at(x, y, c) *= alpha;
        }
      }
  return book;
}

}  // namespace sixway::reference
