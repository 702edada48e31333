#pragma once
// Unity's import settings for a flipbook texture, as the TextureImporter section of the `.meta` file that
// Unity reads beside every asset (docs/formats.md, "Unity import settings"). Written beside each texture so
// that a flipbook dropped into a Unity project imports as the six-way shader expects, with no clicks: linear
// (sRGB off), no power-of-two rescale, no size cap below the texture's own, uncompressed (BC6H drops alpha,
// BC7 and DXT quantise the dark lightmaps), the flipbook's columns × rows.
#include <string>
#include <string_view>

namespace sixway::reference {

struct UnityTextureImport {
  std::string guid;        // 32 hex digits: Unity's asset id (unityGuid)
  bool halfFloat = false;  // EXR: RGBA half (TextureFormat 17); otherwise RGBA 8-bit (TextureFormat 4)
  bool srgb = false;       // colour stored sRGB-encoded (Unity decodes it when sampling; alpha stays linear)
  int width = 1, height = 1;
  int columns = 1, rows = 1;  // the flipbook grid
};

// A stable asset id: the same `seed` gives the same id, so a re-bake keeps the references a Unity project
// holds to the textures. Two 64-bit FNV-1a hashes of the seed with different offsets, as 32 hex digits.
std::string unityGuid(std::string_view seed);

// The `.meta` file's text (YAML, Unity's TextureImporter serialisation).
std::string unityTextureMeta(const UnityTextureImport& texture);

}  // namespace sixway::reference
