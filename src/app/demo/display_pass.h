#pragma once
// The demo's view: panels of the frame's images (the frame, the guiding map, one lightmap channel)
// drawn side by side into one 8-bit display image of the window's size (shaders/demo/display.frag). The
// display image is what the window shows under the user interface, and what screenshots and recordings save.
#include <cstdint>
#include <memory>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/image.h"
#include "io/image.h"

namespace sixway::gpu {
class Context;
class Pipeline;
class PipelineCache;
class Sequence;
}  // namespace sixway::gpu

namespace sixway::app::demo {

enum class PanelKind : int { Frame = 0, Guide = 1, Channel = 2 };

struct Panel {
  const gpu::Image* image = nullptr;  // sampled, VK_IMAGE_LAYOUT_GENERAL
  PanelKind kind = PanelKind::Frame;
  int channel = 0;             // Channel: the image's component, 0..3
  bool channelIsLight = true;  // Channel: scaled by the exposure (alpha is not)
};

// 8-bit RGBA or BGRA texels (sRGB codes) as an RGBA image of the codes / 255, alpha set to 1.
io::Image imageFromDisplayTexels(const std::vector<uint8_t>& texels, uint32_t width, uint32_t height,
                                 VkFormat format);

class DisplayPass {
 public:
  // A width × height display image in `format` (R8G8B8A8 or B8G8R8A8, UNORM or SRGB: what the swapchain
  // blits from without conversion).
  DisplayPass(const gpu::Context& context, const gpu::PipelineCache& cache, uint32_t width, uint32_t height,
              VkFormat format);
  ~DisplayPass();

  // Draws the panels left to right, each letterboxed to its image's aspect ratio in an equal share of the
  // width, over a dark background; waits for the GPU.
  void draw(const std::vector<Panel>& panels, float exposure);

  const gpu::Image& image() const { return image_; }
  // The display image as RGBA in [0, 1] (sRGB codes / 255), for PNGs written without a transfer function.
  io::Image download() const;

 private:
  const gpu::Context& context_;
  gpu::Image image_;
  std::unique_ptr<gpu::Pipeline> pipeline_;
  std::unique_ptr<gpu::Sampler> sampler_;
};

}  // namespace sixway::app::demo
