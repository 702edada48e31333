#include "render/lightmap_packing.h"

#include <stdexcept>

namespace sixway::render {
namespace {

// Two RGBA textures named `first` and `second`, holding the eight channels in the order given.
ChannelPacking twoTextures(const std::string& first, const std::array<SixWayChannel, 4>& firstChannels,
                           const std::string& second, const std::array<SixWayChannel, 4>& secondChannels) {
  ChannelPacking p;
  p.textures = {first, second};
  for (int c = 0; c < 4; ++c) {
    p.slots[firstChannels[c]] = {0, c};
    p.slots[secondChannels[c]] = {1, c};
  }
  return p;
}

}  // namespace

ChannelPacking unityPacking() {
  return twoTextures("A", {Right, Top, Back, Alpha}, "B", {Left, Bottom, Front, Emissive});
}

const std::vector<std::string>& packingPresetNames() {
  static const std::vector<std::string> names = {"unity", "rlt-bbf", "o3de"};
  return names;
}

ChannelPacking packingPreset(const std::string& name) {
  if (name == "unity") return unityPacking();
  if (name == "rlt-bbf")
    return twoTextures("RLT", {Right, Left, Top, Alpha}, "BBF", {Bottom, Back, Front, Emissive});
  if (name == "o3de")
    return twoTextures("TLRB", {Top, Left, Right, Bottom}, "FB", {Front, Back, Emissive, Alpha});
  throw std::invalid_argument("packingPreset: unknown packing " + name);
}

}  // namespace sixway::render
