#pragma once
// The two RGBA lightmap images of a frame in Unity's packing (docs/conventions.md, "Channels and packing"):
// A = (Right, Top, Back, alpha), B = (Left, Bottom, Front, emissive). The network writes them on the GPU;
// reference and flipbook lightmaps, computed as eight-channel images in sixWayChannelNames() order, are
// packed and uploaded here. The shading pass samples them the same way whatever their source.
#include <cstdint>

#include "gpu/image.h"
#include "io/image.h"

namespace sixway::render {

struct LightmapImages {
  // Two RGBA16F images (storage, sampled) of width × height.
  LightmapImages(const gpu::Context& context, uint32_t width, uint32_t height);

  // An eight-channel image (sixWayChannelNames() order, the images' size) packed into A and B.
  // Throws std::invalid_argument for another size or channel count.
  void upload(const io::Image& eightChannels);
  // Back to eight channels, in sixWayChannelNames() order.
  io::Image download() const;

  gpu::Image a, b;
};

}  // namespace sixway::render
