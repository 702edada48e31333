#pragma once
// Flipbooks of six-way lightmaps, the way game engines play them back (docs/conventions.md, "Flipbooks"): the
// frames as tiles of a columns × rows grid, row-major, frame 0 at the top-left, the eight channels packed
// into RGBA textures (Unity's packing unless told otherwise), written as EXR (half, linear) and 8-bit PNG and
// TGA (colour sRGB-encoded, alpha linear) with a JSON sidecar. Flipbooks from other tools are read through a
// description in the sidecar's format, which says where each channel lives (docs/reference-rendering.md,
// "Flipbooks").
#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "io/image.h"
#include "reference/scattering.h"
#include "render/lightmap_packing.h"
#include "render/sixway.h"
#include "render/sixway_shading.h"
#include "scene/scene.h"

namespace sixway::reference {

struct FlipbookLayout {
  int columns = 1, rows = 1;
  int frames = 1;  // tiles in use, at most columns · rows
  int tileWidth = 1, tileHeight = 1;
};

// A near-square grid for `frames` tiles: `columns` columns (0: ceil(√frames)) and as many rows as needed.
FlipbookLayout flipbookLayout(int frames, int tileWidth, int tileHeight, int columns = 0);

// The largest flipbook texture side: Unity's and Unreal's largest texture (16384); a packed RGBA float
// texture of that size is already 4 GiB on the host while it is written.
inline constexpr int kMaxFlipbookSide = 16384;
// Throws io::InputError naming `source` when the layout's textures would be wider or taller than
// kMaxFlipbookSide, with what to reduce.
void requireFlipbookFits(const FlipbookLayout& layout, const std::string& source);

// The packings (render/lightmap_packing.h) the flipbooks are written and read in.
using render::ChannelPacking;
using render::packingPreset;
using render::packingPresetNames;
using render::unityPacking;

// The textures (RGBA, one per packing texture) holding `frames` (eight-channel tiles in sixWayChannelNames()
// order, of the layout's tile size); unused tiles are 0.
std::vector<io::Image> packFlipbook(const std::vector<io::Image>& frames, const FlipbookLayout& layout,
                                    const ChannelPacking& packing);
// The eight-channel frames held by `textures` (RGBA, in packing order).
std::vector<io::Image> unpackFlipbook(const std::vector<io::Image>& textures, const FlipbookLayout& layout,
                                      const ChannelPacking& packing);

// Unity's Single Channel emission (VFX Graph's Six-way Smoke Lit output; VFXLit.hlsl in URP and HDRP) shades
// multiplier · gradient(mask) · opacity, so the emissive component it reads is a straight mask, not sixway's
// premultiplied luminance e (docs/formats.md, "Emission"). With mask = e / (alpha · luminanceScale) the three
// numbers below make Unity's formula give what SixWayShading gives for e with the smoke's straight scale.
struct EmissiveMask {
  float luminanceScale = 1.0f;  // e = alpha · luminanceScale · mask
  std::vector<render::GradientKey>
      gradient;             // Unity's Emissive Gradient: black at 0, positions ≤ 1, colours ≤ 1
  float multiplier = 1.0f;  // Unity's Emissive Multiplier
};
// The mask for `smoke`'s emission; none when it does not emit.
std::optional<EmissiveMask> unityEmissiveMask(const scene::Smoke& smoke);

// Writes <stem>_<texture>.exr (half), .png and .tga (8-bit, colour sRGB-encoded) for each texture of
// `packing`, a Unity .meta file beside each (reference/unity_meta.h), and the sidecar <stem>.json (layout,
// files, channels, colour space, normalisation, the scattering the lightmaps hold when known, and
// `provenance` as given). Returns the sidecar's path. With `emissiveMask` the emissive component holds that
// mask (clamped to [0, 1]) and the sidecar its Unity settings; without, the premultiplied luminance.
std::filesystem::path writeFlipbook(const std::filesystem::path& directory, const std::string& stem,
                                    const std::vector<io::Image>& frames, const FlipbookLayout& layout,
                                    const ChannelPacking& packing, const nlohmann::json& provenance,
                                    std::optional<Scattering> scattering = std::nullopt,
                                    const std::optional<EmissiveMask>& emissiveMask = std::nullopt);

struct Flipbook {
  FlipbookLayout layout;
  std::vector<io::Image> frames;         // eight channels each, premultiplied (emission too), linear
  std::optional<Scattering> scattering;  // as the sidecar says (other tools' descriptions may not)
};

// Reads the flipbook a description (a sidecar of writeFlipbook, or one written by hand for another tool's
// textures) names; texture paths are relative to the description's folder. Throws io::InputError naming the
// description or texture file and the problem.
Flipbook readFlipbook(const std::filesystem::path& description);

}  // namespace sixway::reference
