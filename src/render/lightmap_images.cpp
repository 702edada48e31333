#include "render/lightmap_images.h"

#include <array>
#include <glm/gtc/packing.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/sixway.h"

namespace sixway::render {
namespace {

// Channel (sixWayChannelNames() order) in each RGBA component of A and of B.
constexpr std::array<std::array<int, 4>, 2> kPacking{
    {{Right, Top, Back, Alpha}, {Left, Bottom, Front, Emissive}}};

gpu::ImageDesc lightmapDesc(uint32_t width, uint32_t height, const char* name) {
  gpu::ImageDesc desc;
  desc.width = width;
  desc.height = height;
  desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
  desc.name = name;
  return desc;
}

}  // namespace

LightmapImages::LightmapImages(const gpu::Context& context, uint32_t width, uint32_t height)
    : a(context, lightmapDesc(width, height, "lightmap A")),
      b(context, lightmapDesc(width, height, "lightmap B")) {}

void LightmapImages::upload(const io::Image& eight) {
  if (eight.width != int(a.desc().width) || eight.height != int(a.desc().height) ||
      eight.channelCount() != kSixWayChannels)
    throw std::invalid_argument("LightmapImages::upload: expected " + std::to_string(a.desc().width) + "x" +
                                std::to_string(a.desc().height) + " pixels of 8 channels");
  const size_t pixels = size_t(eight.width) * eight.height;
  for (int t = 0; t < 2; ++t) {
    std::vector<uint16_t> texels(pixels * 4);
    for (size_t p = 0; p < pixels; ++p)
      for (int c = 0; c < 4; ++c) texels[p * 4 + c] = glm::packHalf1x16(eight.pixels[p * 8 + kPacking[t][c]]);
    (t == 0 ? a : b).upload(std::as_bytes(std::span(texels)));
  }
}

io::Image LightmapImages::download() const {
  const auto& names = sixWayChannelNames();
  io::Image eight(int(a.desc().width), int(a.desc().height), {names.begin(), names.end()});
  const size_t pixels = size_t(eight.width) * eight.height;
  for (int t = 0; t < 2; ++t) {
    const std::vector<uint16_t> texels = (t == 0 ? a : b).download<uint16_t>();
    for (size_t p = 0; p < pixels; ++p)
      for (int c = 0; c < 4; ++c)
        eight.pixels[p * 8 + kPacking[t][c]] = glm::unpackHalf1x16(texels[p * 4 + c]);
  }
  return eight;
}

}  // namespace sixway::render
