#include "reference/unity_meta.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>

namespace sixway::render {
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
  std::string meta;
  meta += "fileFormatVersion: 2\n";
  meta += "guid: " + t.guid + "\n";
  meta += "TextureImporter:\n";
  meta += "  serializedVersion: 12\n";
  meta += "  mipmaps:\n";
  meta += "    mipMapMode: 0\n";
  meta += "    enableMipMap: 0\n";
  meta += std::string("    sRGBTexture: ") + (t.srgb ? "1" : "0") + "\n";
  meta += "    linearTexture: 0\n";
  meta += "  isReadable: 0\n";
  meta += "  textureFormat: 1\n";
  meta += "  maxTextureSize: " + std::to_string(cap) + "\n";
  meta += "  textureSettings:\n";
  meta += "    serializedVersion: 2\n";
  meta += "    filterMode: 1\n";
  meta += "    wrapU: 1\n";
  meta += "    wrapV: 1\n";
  meta += "    wrapW: 1\n";
  meta += "  nPOTScale: 0\n";
  meta += "  alphaUsage: 1\n";
  meta += "  alphaIsTransparency: 0\n";
  meta += "  textureType: 0\n";
  meta += "  textureShape: 1\n";
  meta += "  flipbookRows: " + std::to_string(t.rows) + "\n";
  meta += "  flipbookColumns: " + std::to_string(t.columns) + "\n";
  meta += "  maxTextureSizeSet: 0\n";
  meta += "  textureFormatSet: 0\n";
  meta += "  platformSettings:\n";
  meta += "  - serializedVersion: 3\n";
  meta += "    buildTarget: DefaultTexturePlatform\n";
  meta += "    maxTextureSize: " + std::to_string(cap) + "\n";
  meta += "    resizeAlgorithm: 0\n";
  meta += "    textureFormat: " + std::to_string(format) + "\n";
  meta += "    textureCompression: 0\n";
  meta += "    overridden: 0\n";
  meta += "  userData:\n";
  meta += "  assetBundleName:\n";
  meta += "  assetBundleVariant:\n";
  return meta;
}

}  // namespace sixway::render
