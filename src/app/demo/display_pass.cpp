#include "app/demo/display_pass.h"

#include <algorithm>

#include "app/demo/demo_spec.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"

namespace sixway::app::demo {
namespace {

struct DisplayPush {  // shaders/demo/display.frag
  int kind;
  int channel;
  float exposure;
  int channelIsLight;
};

bool isSrgb(VkFormat format) {
  return format == VK_FORMAT_R8G8B8A8_SRGB || format == VK_FORMAT_B8G8R8A8_SRGB;
}

bool isBgra(VkFormat format) {
  return format == VK_FORMAT_B8G8R8A8_UNORM || format == VK_FORMAT_B8G8R8A8_SRGB;
}

// The largest rectangle of the image's aspect ratio centred in `cell`.
VkRect2D letterbox(VkRect2D cell, uint32_t imageWidth, uint32_t imageHeight) {
  const double scale =
      std::min(double(cell.extent.width) / imageWidth, double(cell.extent.height) / imageHeight);
  const uint32_t w = std::max(1u, uint32_t(imageWidth * scale)),
                 h = std::max(1u, uint32_t(imageHeight * scale));
  return {{cell.offset.x + int32_t(cell.extent.width - w) / 2,
           cell.offset.y + int32_t(cell.extent.height - h) / 2},
          {w, h}};
}

}  // namespace

DisplayPass::DisplayPass(const gpu::Context& context, const gpu::PipelineCache& cache, uint32_t width,
                         uint32_t height, VkFormat format)
    : context_(context) {
  gpu::ImageDesc desc;
  desc.width = width;
  desc.height = height;
  desc.format = format;
  desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  desc.name = "display";
  image_ = gpu::Image(context, desc);
  gpu::GraphicsPipelineDesc p;
  p.vertexShader = "demo/display.vert";
  p.fragmentShader = "demo/display.frag";
  p.bindings = {gpu::BindingType::SampledImage};
  p.pushConstantBytes = sizeof(DisplayPush);
  p.spec.set(spec::kEncodeSrgb, !isSrgb(format));
  p.colorFormats = {format};
  pipeline_ = std::make_unique<gpu::Pipeline>(context, cache, p);
  sampler_ = std::make_unique<gpu::Sampler>(context, VK_FILTER_LINEAR);
}

DisplayPass::~DisplayPass() = default;

void DisplayPass::draw(const std::vector<Panel>& panels, float exposure) {
  const uint32_t width = image_.desc().width, height = image_.desc().height;
  std::vector<gpu::Draw> draws;
  const uint32_t n = uint32_t(std::max<size_t>(panels.size(), 1));
  for (uint32_t i = 0; i < panels.size(); ++i) {
    const Panel& panel = panels[i];
    const VkRect2D cell{{int32_t(width * i / n), 0}, {width / n, height}};
    gpu::Draw d;
    d.pipeline = pipeline_.get();
    d.bindings = {gpu::samples(*panel.image, *sampler_)};
    d.pushConstants =
        gpu::pushBytes(DisplayPush{int(panel.kind), panel.channel, exposure, panel.channelIsLight ? 1 : 0});
    d.count = 3;
    d.area = letterbox(cell, panel.image->desc().width, panel.image->desc().height);
    draws.push_back(std::move(d));
  }
  // Recorded every call: the panels change with what the user looks at, and recording is cheap.
  gpu::Sequence sequence(context_);
  sequence.render({.colors = {&image_}, .clearColor = std::array<float, 4>{0.06f, 0.06f, 0.07f, 1.0f}},
                  draws);
  sequence.finish();
  sequence.submit();
}

io::Image imageFromDisplayTexels(const std::vector<uint8_t>& texels, uint32_t width, uint32_t height,
                                 VkFormat format) {
  io::Image out(int(width), int(height), {"R", "G", "B", "A"});
  const bool bgra = isBgra(format);
  for (size_t i = 0; i < texels.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) out.pixels[i + c] = texels[i + (bgra ? 2 - c : c)] / 255.0f;
    out.pixels[i + 3] = 1.0f;  // what is shown is opaque
  }
  return out;
}

io::Image DisplayPass::download() const {
  return imageFromDisplayTexels(image_.download<uint8_t>(), image_.desc().width, image_.desc().height,
                                image_.desc().format);
}

}  // namespace sixway::app::demo
