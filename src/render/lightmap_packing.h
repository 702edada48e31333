#pragma once
// Where the eight six-way channels go in an engine's textures (docs/formats.md, "Packing presets"): the
// packings `sixway bake --packing` writes flipbooks in and the runtime gives its lightmaps in
// (RendererOptions::packing).
#include <array>
#include <string>
#include <vector>

#include "render/sixway.h"

namespace sixway::render {

// Where each six-way channel lives: a texture (by index into `textures`) and a component 0..3 (R, G, B, A).
// A channel without a texture reads as 0 (only emissive may be absent).
struct ChannelPacking {
  struct Slot {
    int texture = -1;
    int component = 0;
  };
  std::vector<std::string> textures;
  std::array<Slot, render::kSixWayChannels> slots;
};

// Unity VFX Graph's six-way packing: A = (Right, Top, Back, alpha), B = (Left, Bottom, Front, emissive).
ChannelPacking unityPacking();
// The packings `sixway bake --packing` offers (docs/formats.md, "Packing presets"): "unity" (the above),
// "rlt-bbf" (RLT = (Right, Left, Top, alpha), BBF = (Bottom, Back, Front, emissive): O3DE's RtLftTp_BtBckFr
// mode, the layout of EmberGen-style exports) and "o3de" (O3DE's default TpLftRtBt_FrBck mode: TLRB = (Top,
// Left, Right, Bottom), FB = (Front, Back, emissive, alpha), alpha where O3DE's packed opacity reads it).
ChannelPacking packingPreset(const std::string& name);
const std::vector<std::string>& packingPresetNames();

}  // namespace sixway::render
