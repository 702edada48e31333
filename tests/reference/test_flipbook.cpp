// Flipbook layout, Unity packing, the files and sidecar written, and reading flipbooks back through a
// description, including another tool's packing.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "io/exr.h"
#include "io/png.h"
#include "io/tga.h"
#include "reference/flipbook.h"
#include "support/input_error.h"
#include "support/temp_dir.h"

namespace sixway::test {
namespace {

using reference::FlipbookLayout;

// Frame f, channel c, pixel (x, y) holds a value that names all four.
float code(int f, int c, int x, int y) {
  return float(f * 8 + c) / 64.0f + float(x + 3 * y) / 4096.0f;
}

std::vector<io::Image> codedFrames(int frames, int w, int h) {
  std::vector<io::Image> result;
  const auto& names = render::sixWayChannelNames();
  for (int f = 0; f < frames; ++f) {
    io::Image tile(w, h, {names.begin(), names.end()});
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 8; ++c) tile.at(x, y, c) = code(f, c, x, y);
    result.push_back(tile);
  }
  return result;
}

void expectFramesNear(const std::vector<io::Image>& actual, const std::vector<io::Image>& expected,
                      float tolerance) {
  ASSERT_EQ(actual.size(), expected.size());
  for (size_t f = 0; f < actual.size(); ++f) {
    ASSERT_EQ(actual[f].channels, expected[f].channels);
    for (size_t i = 0; i < actual[f].pixels.size(); ++i)
      ASSERT_NEAR(actual[f].pixels[i], expected[f].pixels[i], tolerance) << "frame " << f << " value " << i;
  }
}

TEST(FlipbookLayoutTest, IsANearSquareRowMajorGrid) {
  const FlipbookLayout five = reference::flipbookLayout(5, 16, 8);
  EXPECT_EQ(five.columns, 3);
  EXPECT_EQ(five.rows, 2);
  EXPECT_EQ(reference::flipbookLayout(16, 4, 4).columns, 4);
  EXPECT_EQ(reference::flipbookLayout(1, 4, 4).rows, 1);
  const FlipbookLayout strip = reference::flipbookLayout(6, 4, 4, 6);
  EXPECT_EQ(strip.columns, 6);
  EXPECT_EQ(strip.rows, 1);
}

TEST(FlipbookLayoutTest, TexturesBeyondTheLargestSideAreRefused) {
  EXPECT_NO_THROW(
      reference::requireFlipbookFits(reference::flipbookLayout(64, 2048, 2048), "--frames/--tile"));
  EXPECT_THAT(inputErrorMessage([] {
                reference::requireFlipbookFits(reference::flipbookLayout(64, 4096, 4096), "--frames/--tile");
              }),
              namesFileAndProblem("--frames/--tile",
                                  "make a 32768x32768 flipbook, more than 16384 per side; "
                                  "reduce the frames or the tile size"));
  // One long row: the width alone.
  EXPECT_THROW(reference::requireFlipbookFits(reference::flipbookLayout(100, 256, 256, 100), "flipbook"),
               io::InputError);
}

// Unity: A = (Right, Top, Back, alpha), B = (Left, Bottom, Front, emissive); frame f at column f % columns,
// row f / columns, row 0 at the top of the texture.
TEST(FlipbookPackingTest, PlacesFramesAndChannelsAsUnityExpects) {
  const FlipbookLayout layout = reference::flipbookLayout(5, 4, 3);
  const auto textures = reference::packFlipbook(codedFrames(5, 4, 3), layout, reference::unityPacking());
  ASSERT_EQ(textures.size(), 2u);
  ASSERT_EQ(textures[0].width, 12);
  ASSERT_EQ(textures[0].height, 6);
  const int a[4] = {render::Right, render::Top, render::Back, render::Alpha};
  const int b[4] = {render::Left, render::Bottom, render::Front, render::Emissive};
  for (int f = 0; f < 5; ++f)
    for (int k = 0; k < 4; ++k) {
      const int x = 1, y = 2, tx = (f % 3) * 4 + x, ty = (f / 3) * 3 + y;
      EXPECT_EQ(textures[0].at(tx, ty, k), code(f, a[k], x, y)) << f << " " << k;
      EXPECT_EQ(textures[1].at(tx, ty, k), code(f, b[k], x, y)) << f << " " << k;
    }
  EXPECT_EQ(textures[0].at(11, 5, 3), 0.0f) << "the unused sixth tile is transparent";
  expectFramesNear(reference::unpackFlipbook(textures, layout, reference::unityPacking()),
                   codedFrames(5, 4, 3), 0.0f);
}

// Each preset's two textures hold, component by component, the channels docs/formats.md lists for it.
TEST(FlipbookPackingTest, PresetsPlaceTheChannelsAsDocumented) {
  using render::Alpha, render::Back, render::Bottom, render::Emissive, render::Front, render::Left,
      render::Right, render::Top;
  struct Expected {
    std::string preset, first, second;
    std::array<int, 4> firstChannels, secondChannels;
  };
  const std::vector<Expected> presets = {
      {"unity", "A", "B", {Right, Top, Back, Alpha}, {Left, Bottom, Front, Emissive}},
      {"rlt-bbf", "RLT", "BBF", {Right, Left, Top, Alpha}, {Bottom, Back, Front, Emissive}},
      {"o3de", "TLRB", "FB", {Top, Left, Right, Bottom}, {Front, Back, Emissive, Alpha}}};
  ASSERT_EQ(reference::packingPresetNames().size(), presets.size());
  const FlipbookLayout layout = reference::flipbookLayout(2, 4, 3);
  for (const Expected& e : presets) {
    const reference::ChannelPacking packing = reference::packingPreset(e.preset);
    EXPECT_THAT(packing.textures, ::testing::ElementsAre(e.first, e.second));
    const auto textures = reference::packFlipbook(codedFrames(2, 4, 3), layout, packing);
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(textures[0].at(4 + 2, 1, k), code(1, e.firstChannels[k], 2, 1)) << e.preset << " " << k;
      EXPECT_EQ(textures[1].at(4 + 2, 1, k), code(1, e.secondChannels[k], 2, 1)) << e.preset << " " << k;
    }
    expectFramesNear(reference::unpackFlipbook(textures, layout, packing), codedFrames(2, 4, 3), 0.0f);
  }
  EXPECT_THROW(reference::packingPreset("unreal5"), std::invalid_argument);
}

class FlipbookFilesTest : public ::testing::Test {
 protected:
  void writeDescription(const nlohmann::json& description) {
    std::ofstream(dir / "book.json") << description.dump(2);
  }
  TempDir dir;
};

TEST_F(FlipbookFilesTest, WritesExrPngTgaAndASidecarThatReadsBack) {
  const FlipbookLayout layout = reference::flipbookLayout(3, 5, 4);
  const auto frames = codedFrames(3, 5, 4);
  const auto sidecar = reference::writeFlipbook(dir.path(), "flipbook", frames, layout,
                                                reference::unityPacking(), {{"note", "test"}});
  for (const char* file : {"flipbook_A.exr", "flipbook_A.png", "flipbook_A.tga", "flipbook_B.exr",
                           "flipbook_B.png", "flipbook_B.tga", "flipbook.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / file)) << file;
  EXPECT_EQ(io::readExr(dir / "flipbook_A.exr").attributes.at("colorspace"), "linear");
  // PNG and TGA hold the same 8-bit codes: colour sRGB-encoded (IEC 61966-2-1), alpha (here emissive) linear.
  const auto srgb = [](float v) {
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1 / 2.4f) - 0.055f;
  };
  const io::Image png = io::readPng(dir / "flipbook_B.png");
  EXPECT_NEAR(png.at(6, 1, 2), srgb(code(1, render::Front, 1, 1)), 0.5f / 255);
  EXPECT_NEAR(png.at(6, 1, 3), code(1, render::Emissive, 1, 1), 0.5f / 255);
  EXPECT_EQ(io::readTga(dir / "flipbook_B.tga").pixels, png.pixels);

  const nlohmann::json json = nlohmann::json::parse(std::ifstream(sidecar));
  EXPECT_EQ(json["channels"]["back"], "A.B");
  EXPECT_EQ(json["channels"]["emissive"], "B.A");
  EXPECT_EQ(json["color_space"], "srgb");
  EXPECT_EQ(json["eight_bit"]["clipped_fraction"], 0.0);
  EXPECT_EQ(json["layout"]["columns"], 2);
  const reference::Flipbook book = reference::readFlipbook(sidecar);
  EXPECT_EQ(book.layout.frames, 3);
  expectFramesNear(book.frames, frames, 2e-4f);  // EXR half
  // The sidecar naming only the PNGs: they read back through its color_space, within half an sRGB code at 1.
  nlohmann::json pngOnly = json;
  pngOnly["textures"] = {{"A", "flipbook_A.png"}, {"B", "flipbook_B.png"}};
  writeDescription(pngOnly);
  expectFramesNear(reference::readFlipbook(dir / "book.json").frames, frames, 6e-3f);
}

// By default the emissive component is Unity's Single Channel mask e / (alpha · luminance scale),
// which Unity multiplies by opacity; the sidecar holds the scale and Unity's settings, and readFlipbook turns
// the mask back into the premultiplied luminance.
TEST_F(FlipbookFilesTest, AnEmissiveMaskReadsBackAsPremultipliedLuminance) {
  const FlipbookLayout layout = reference::flipbookLayout(3, 5, 4);
  auto frames = codedFrames(3, 5, 4);
  frames[2].at(1, 1, render::Emissive) = 1.5f;  // over the mask's 1: clamped
  frames[1].at(2, 3, render::Alpha) = 0.0f;     // no opacity: no emission
  const reference::EmissiveMask mask{
      .luminanceScale = 2.0f,
      .gradient = {{0.0f, glm::vec3(0.0f)}, {1.0f, glm::vec3(1.0f, 0.5f, 0.25f)}},
      .multiplier = 3.0f};
  const auto sidecar =
      reference::writeFlipbook(dir.path(), "flipbook", frames, layout, reference::unityPacking(),
                               {{"note", "test"}}, std::nullopt, mask);
  const nlohmann::json json = nlohmann::json::parse(std::ifstream(sidecar));
  EXPECT_EQ(json["emissive"]["encoding"], "mask");
  EXPECT_EQ(json["emissive"]["luminance_scale"], 2.0);
  EXPECT_EQ(json["emissive"]["unity"]["emissive_mode"], "Single Channel");
  EXPECT_EQ(json["emissive"]["unity"]["emissive_multiplier"], 3.0);
  EXPECT_EQ(json["emissive"]["unity"]["emissive_gradient"].size(), 2u);
  const io::Image b = io::readExr(dir / "flipbook_B.exr").image;
  const reference::Flipbook book = reference::readFlipbook(sidecar);
  for (int f = 0; f < 3; ++f)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 5; ++x) {
        const float alpha = frames[f].at(x, y, render::Alpha), e = frames[f].at(x, y, render::Emissive);
        const float expected = alpha > 0.0f ? std::min(e / (alpha * 2.0f), 1.0f) : 0.0f;
        const int tx = (f % layout.columns) * 5 + x, ty = (f / layout.columns) * 4 + y;
        EXPECT_NEAR(b.at(tx, ty, *b.channelIndex("A")), expected, 1e-3f) << f << " " << x << " " << y;
        EXPECT_NEAR(book.frames[f].at(x, y, render::Emissive), alpha * 2.0f * expected, 1e-3f);
      }
  EXPECT_NEAR(book.frames[0].at(3, 2, render::Emissive), frames[0].at(3, 2, render::Emissive), 1e-3f);
  // Without a mask the component holds e itself, and says so.
  reference::writeFlipbook(dir.path(), "plain", frames, layout, reference::unityPacking(),
                           {{"note", "test"}});
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(dir / "plain.json"))["emissive"]["encoding"],
            "premultiplied");
  expectFramesNear(reference::readFlipbook(dir / "plain.json").frames, frames, 2e-3f);
}

// The value of `key` in a Unity .meta file: the first line "<indent><key>: <value>" after the line `after`
// (so that the platform settings' textureFormat is told from the importer's own).
std::string metaValue(const std::filesystem::path& file, const std::string& key,
                      const std::string& after = "") {
  std::ifstream in(file);
  bool found = after.empty();
  for (std::string line; std::getline(in, line);) {
    if (!found) {
      found = line.find(after) != std::string::npos;
      continue;
    }
    const std::size_t start = line.find_first_not_of(" -");
    if (start != std::string::npos && line.compare(start, key.size() + 2, key + ": ") == 0)
      return line.substr(start + key.size() + 2);
  }
  return "(no " + key + ")";
}

// Each texture has Unity's import settings beside it: linear, no rescale, uncompressed RGBA half
// for EXR (BC6H would drop alpha) and RGBA 8-bit for PNG/TGA, the flipbook grid; a stable id per texture.
TEST_F(FlipbookFilesTest, WritesUnityImportSettingsBesideEachTexture) {
  const FlipbookLayout layout = reference::flipbookLayout(5, 48, 40);  // 3 × 2 tiles: 144 × 80 pixels
  const auto frames = codedFrames(5, 48, 40);
  reference::writeFlipbook(dir.path(), "book", frames, layout, reference::unityPacking(), {{"source", "a"}});
  for (const char* texture : {"book_A", "book_B"})
    for (const std::string extension : {".exr", ".png", ".tga"}) {
      const std::filesystem::path meta = dir / (texture + extension + ".meta");
      ASSERT_TRUE(std::filesystem::exists(meta)) << meta;
      EXPECT_EQ(metaValue(meta, "fileFormatVersion"), "2");
      EXPECT_THAT(metaValue(meta, "guid"), ::testing::MatchesRegex("[0-9a-f]{32}"));
      EXPECT_EQ(metaValue(meta, "sRGBTexture"), extension == ".exr" ? "0" : "1") << meta;
      EXPECT_EQ(metaValue(meta, "nPOTScale"), "0");
      EXPECT_EQ(metaValue(meta, "enableMipMap"), "0");
      EXPECT_EQ(metaValue(meta, "alphaUsage"), "1");
      EXPECT_EQ(metaValue(meta, "flipbookColumns"), "3");
      EXPECT_EQ(metaValue(meta, "flipbookRows"), "2");
      EXPECT_EQ(metaValue(meta, "maxTextureSize", "buildTarget: DefaultTexturePlatform"), "256");
      EXPECT_EQ(metaValue(meta, "textureFormat", "buildTarget: DefaultTexturePlatform"),
                extension == ".exr" ? "17" : "4");
      EXPECT_EQ(metaValue(meta, "textureCompression", "buildTarget: DefaultTexturePlatform"), "0");
    }
  // Every texture its own id; the same source gives the same ids again, another source other ids.
  const std::string a = metaValue(dir / "book_A.exr.meta", "guid");
  EXPECT_NE(a, metaValue(dir / "book_A.png.meta", "guid"));
  EXPECT_NE(a, metaValue(dir / "book_B.exr.meta", "guid"));
  reference::writeFlipbook(dir.path(), "book", frames, layout, reference::unityPacking(), {{"source", "a"}});
  EXPECT_EQ(metaValue(dir / "book_A.exr.meta", "guid"), a);
  reference::writeFlipbook(dir.path(), "book", frames, layout, reference::unityPacking(), {{"source", "b"}});
  EXPECT_NE(metaValue(dir / "book_A.exr.meta", "guid"), a);
}

// Another tool's packing (here EmberGen-style "RLT"/"BBF" textures as TGA: R = Right, G = Left, B = Top,
// A = alpha; R = Bottom, G = Back, B = Front, A = emissive), read through a hand-written description.
TEST_F(FlipbookFilesTest, ReadsAnotherToolsPackingThroughADescription) {
  reference::ChannelPacking rltBbf;
  rltBbf.textures = {"RLT", "BBF"};
  rltBbf.slots[render::Right] = {0, 0};
  rltBbf.slots[render::Left] = {0, 1};
  rltBbf.slots[render::Top] = {0, 2};
  rltBbf.slots[render::Alpha] = {0, 3};
  rltBbf.slots[render::Bottom] = {1, 0};
  rltBbf.slots[render::Back] = {1, 1};
  rltBbf.slots[render::Front] = {1, 2};
  rltBbf.slots[render::Emissive] = {1, 3};
  const FlipbookLayout layout = reference::flipbookLayout(4, 6, 5);
  const auto frames = codedFrames(4, 6, 5);
  const auto textures = reference::packFlipbook(frames, layout, rltBbf);
  io::writeTga(dir / "smoke_RLT.tga", textures[0]);
  io::writeTga(dir / "smoke_BBF.tga", textures[1]);
  writeDescription({{"layout", {{"columns", 2}, {"rows", 2}, {"tile_width", 6}, {"tile_height", 5}}},
                    {"textures", {{"RLT", "smoke_RLT.tga"}, {"BBF", "smoke_BBF.tga"}}},
                    {"channels",
                     {{"right", "RLT.R"},
                      {"left", "RLT.G"},
                      {"top", "RLT.B"},
                      {"alpha", "RLT.A"},
                      {"bottom", "BBF.R"},
                      {"back", "BBF.G"},
                      {"front", "BBF.B"},
                      {"emissive", "BBF.A"}}}});
  expectFramesNear(reference::readFlipbook(dir / "book.json").frames, frames, 0.5f / 255 + 1e-6f);
}

// sRGB-encoded 8-bit textures are decoded (colour channels only); straight-alpha lightmaps are premultiplied.
TEST_F(FlipbookFilesTest, DecodesSrgbAndPremultipliesStraightAlpha) {
  io::Image a(1, 1, {"R", "G", "B", "A"}), b(1, 1, {"R", "G", "B", "A"});
  a.pixels = {0.5f, 0.5f, 0.5f, 0.5f};
  b.pixels = {0.5f, 0.5f, 0.5f, 0.0f};
  io::writePng(dir / "a.png", a, io::ByteEncoding::Linear);  // codes as given: read as sRGB below
  io::writePng(dir / "b.png", b, io::ByteEncoding::Linear);
  writeDescription({{"layout", {{"columns", 1}, {"rows", 1}, {"tile_width", 1}, {"tile_height", 1}}},
                    {"textures", {{"A", "a.png"}, {"B", "b.png"}}},
                    {"channels",
                     {{"right", "A.R"},
                      {"top", "A.G"},
                      {"back", "A.B"},
                      {"alpha", "A.A"},
                      {"left", "B.R"},
                      {"bottom", "B.G"},
                      {"front", "B.B"}}},
                    {"color_space", "srgb"},
                    {"premultiplied", false}});
  const io::Image frame = reference::readFlipbook(dir / "book.json").frames.at(0);
  const float decoded = std::pow((128 / 255.0f + 0.055f) / 1.055f, 2.4f);
  EXPECT_NEAR(frame.at(0, 0, render::Alpha), 128 / 255.0f, 1e-6f) << "alpha is never sRGB-decoded";
  EXPECT_NEAR(frame.at(0, 0, render::Right), decoded * 128 / 255.0f, 1e-6f);
  EXPECT_NEAR(frame.at(0, 0, render::Left), decoded * 128 / 255.0f, 1e-6f);
  EXPECT_EQ(frame.at(0, 0, render::Emissive), 0.0f) << "no emissive channel reads as 0";
}

TEST_F(FlipbookFilesTest, BadDescriptionsAreOneLineErrors) {
  io::Image rgba(2, 2, {"R", "G", "B", "A"});
  io::writePng(dir / "t.png", rgba, io::ByteEncoding::Linear);
  const nlohmann::json layout = {{"columns", 1}, {"rows", 1}, {"tile_width", 2}, {"tile_height", 2}};
  const nlohmann::json channels = {{"right", "T.R"}, {"left", "T.G"},  {"top", "T.B"},  {"bottom", "T.R"},
                                   {"back", "T.G"},  {"front", "T.B"}, {"alpha", "T.A"}};
  const auto file = dir / "book.json";
  auto problem = [&](nlohmann::json description) {
    writeDescription(description);
    return inputErrorMessage([&] { reference::readFlipbook(file); });
  };
  const nlohmann::json good = {{"layout", layout}, {"textures", {{"T", "t.png"}}}, {"channels", channels}};
  EXPECT_NO_THROW(reference::readFlipbook((writeDescription(good), file)));

  nlohmann::json d = good;
  d["channels"].erase("alpha");
  EXPECT_THAT(problem(d), namesFileAndProblem(file, "channels.alpha: required key missing"));
  d = good;
  d["channels"]["top"] = "T.X";
  EXPECT_THAT(problem(d), namesFileAndProblem(file, "channels.top: must be \"<texture>.<R|G|B|A>\""));
  d = good;
  d["channels"]["top"] = "U.R";
  EXPECT_THAT(problem(d), namesFileAndProblem(file, "naming one of the textures"));
  d = good;
  d["layout"]["tile_width"] = 3;
  EXPECT_THAT(problem(d), namesFileAndProblem(dir / "t.png", "the layout needs 3x2"));
  d = good;
  d["colour_space"] = "linear";
  EXPECT_THAT(problem(d), namesFileAndProblem(file, "colour_space: unknown key"));
  d = good;
  d["textures"]["T"] = "missing.png";
  EXPECT_THAT(problem(d), namesFileAndProblem(dir / "missing.png", "no such file"));
  d = good;
  d["layout"]["frames"] = 2;
  EXPECT_THAT(problem(d), namesFileAndProblem(file, "layout.frames: must be in [1, 1]"));
  d = good;
  d["emissive"] = {{"encoding", "straight"}};
  EXPECT_THAT(problem(d),
              namesFileAndProblem(file, "emissive.encoding: must be one of \"mask\", \"premultiplied\""));
  d["emissive"] = {{"encoding", "mask"}};
  EXPECT_THAT(problem(d), namesFileAndProblem(file, "emissive.luminance_scale: required key missing"));
  d = good;
  d["scattering"] = "double";
  EXPECT_THAT(problem(d), namesFileAndProblem(file, "scattering: must be one of \"single\", \"multiple\""));
  EXPECT_FALSE(reference::readFlipbook((writeDescription(good), file)).scattering)
      << "another tool's: unknown";
}

}  // namespace
}  // namespace sixway::test
