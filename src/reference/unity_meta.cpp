#include "reference/unity_meta.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <vector>

namespace sixway::reference {
namespace {

// UnityEngine.TextureFormat values.
constexpr int kRgba32 = 4;
constexpr int kRgbaHalf = 17;

uint64_t fnv1a(std::string_view text, uint64_t offset) {
  uint64_t hash = offset;
  for (const unsigned char c : text) {
    hash ^= c;
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

// Unity's texture size caps are powers of two from 32 to 16384: the smallest that does not shrink the
// texture.
int sizeCap(int side) {
  int cap = 32;
  while (cap < side && cap < 16384) cap *= 2;
  return cap;
}

}  // namespace

std::string unityGuid(std::string_view seed) {
  char text[33];
  std::snprintf(text, sizeof(text), "%016llx%016llx", (unsigned long long)fnv1a(seed, 0xcbf29ce484222325ULL),
                (unsigned long long)fnv1a(seed, 0x84222325cbf29ce4ULL));
  return text;
}

std::string unityTextureMeta(const UnityTextureImport& t) {
  const int format = t.halfFloat ? kRgbaHalf : kRgba32;
  const int cap = sizeCap(std::max(t.width, t.height));
  // Premultiplied lightmaps: alphaIsTransparency stays off, since its colour dilation would put light into
  // the texels of alpha 0. Mipmaps off: a flipbook's tiles would bleed into each other at the lower levels.
  static constexpr const char* kTemplate = R"(fileFormatVersion: 2
guid: %s
TextureImporter:
  serializedVersion: 12
  mipmaps:
    mipMapMode: 0
    enableMipMap: 0
    sRGBTexture: %d
    linearTexture: 0
  isReadable: 0
  textureFormat: 1
  maxTextureSize: %d
  textureSettings:
    serializedVersion: 2
    filterMode: 1
    wrapU: 1
    wrapV: 1
    wrapW: 1
  nPOTScale: 0
  alphaUsage: 1
  alphaIsTransparency: 0
  textureType: 0
  textureShape: 1
  flipbookRows: %d
  flipbookColumns: %d
  maxTextureSizeSet: 0
  textureFormatSet: 0
  platformSettings:
  - serializedVersion: 3
    buildTarget: DefaultTexturePlatform
    maxTextureSize: %d
    resizeAlgorithm: 0
    textureFormat: %d
    textureCompression: 0
    overridden: 0
  userData:
  assetBundleName:
  assetBundleVariant:
)";
  std::vector<char> text(4096);
  const int length = std::snprintf(text.data(), text.size(), kTemplate, t.guid.c_str(), t.srgb ? 1 : 0, cap,
                                   t.rows, t.columns, cap, format);
  return std::string(text.data(), std::size_t(length));
}

}  // namespace sixway::reference
