#pragma once
// An "engine" for the runtime's tests: sixway's own device borrowed through the public API (EngineDevice),
// colour and depth targets of its own, one command buffer and fence, frames recorded and waited for; the
// small plume scene without its obstacle and a camera on it; image comparisons.
#include <sixway/device.h>
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/gtc/packing.hpp>
#include <nlohmann/json.hpp>
#include <span>
#include <vector>

#include "gpu/check.h"
#include "gpu/device_features.h"
#include "gpu/image.h"
#include "runtime/internal.h"

namespace sixway::test {

inline const std::filesystem::path kScene =
    std::filesystem::path(SIXWAY_TEST_DATA_DIR) / "scenes/small_plume.json";
inline const std::filesystem::path kWeights =
    std::filesystem::path(SIXWAY_TEST_DATA_DIR) / "nn/tiny.safetensors";

// small_plume without its obstacle: an engine target has no obstacle pass, so the images compare everywhere.
inline std::filesystem::path sceneWithoutObstacles(const std::filesystem::path& dir) {
  std::ifstream in(kScene);
  nlohmann::json scene = nlohmann::json::parse(in);
  scene.erase("obstacles");
  const std::filesystem::path file = dir / "plume_no_obstacles.json";
  std::ofstream(file) << scene.dump();
  return file;
}

inline Camera sceneCamera() {
  Camera camera;
  camera.position = {0.0f, 0.64f, 2.4f};
  camera.target = {0.0f, 0.64f, 0.0f};
  camera.fovYDegrees = 40.0f;
  camera.near = 0.1f;
  camera.far = 20.0f;
  return camera;
}

inline double maxDifference(const std::vector<float>& a, const std::vector<float>& b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, double(std::abs(a[i] - b[i])));
  return worst;
}

// An engine's colour and depth targets on sixway's own device, cleared as its scene pass would leave them.
struct EngineTargets {
  EngineTargets(const gpu::Context& context, uint32_t width, uint32_t height,
                VkFormat depthFormat = VK_FORMAT_D32_SFLOAT)
      : color(context, {width, height, 1, VK_FORMAT_R16G16B16A16_SFLOAT,
                        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                            VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                        "engine colour"}),
        depth(context, {width, height, 1, depthFormat,
                        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                            VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                        "engine depth"}) {}
  RenderTarget target() const {
    return {color.handle(), color.view(),        color.desc().format, depth.handle(),
            depth.view(),   depth.desc().format, color.desc().width,  color.desc().height};
  }
  void recordClear(VkCommandBuffer commands, const float background[4], bool clearDepthToo = true) const {
    VkClearColorValue clearColor;
    std::copy(background, background + 4, clearColor.float32);
    VkImageSubresourceRange colorRange{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(commands, color.handle(), VK_IMAGE_LAYOUT_GENERAL, &clearColor, 1, &colorRange);
    if (!clearDepthToo) return;
    VkClearDepthStencilValue clearDepth{1.0f, 0};
    VkImageSubresourceRange depthRange{VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
    if (gpu::hasStencil(depth.desc().format)) depthRange.aspectMask |= VK_IMAGE_ASPECT_STENCIL_BIT;
    vkCmdClearDepthStencilImage(commands, depth.handle(), VK_IMAGE_LAYOUT_GENERAL, &clearDepth, 1,
                                &depthRange);
  }
  // The colour target's RGBA values.
  std::vector<float> colorPixels() const {
    std::vector<float> pixels;
    for (uint16_t h : color.download<uint16_t>()) pixels.push_back(glm::unpackHalf1x16(h));
    return pixels;
  }
  // Fills the depth buffer with `values` (0..1, row 0 at the top) in its format.
  void uploadDepth(const std::vector<double>& values) {
    const VkFormat format = depth.desc().format;
    if (format == VK_FORMAT_D32_SFLOAT) {
      const std::vector<float> texels(values.begin(), values.end());
      depth.upload(std::as_bytes(std::span(texels)));
    } else if (format == VK_FORMAT_D16_UNORM) {
      std::vector<uint16_t> texels;
      for (double v : values) texels.push_back(uint16_t(std::lround(v * 65535.0)));
      depth.upload(std::as_bytes(std::span(texels)));
    } else {  // D24 in the low 24 bits of 32
      std::vector<uint32_t> texels;
      for (double v : values) texels.push_back(uint32_t(std::lround(v * 16777215.0)));
      depth.upload(std::as_bytes(std::span(texels)));
    }
  }
  gpu::Image color, depth;
};

// One primary command buffer of the engine's, with its pool and fence: recorded, submitted and waited for
// (the engine's own wait, which sixway does not count).
struct EngineCommands {
  explicit EngineCommands(const gpu::Context& context) : context(context) {
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = context.queueFamily();
    SIXWAY_VK(vkCreateCommandPool(context.device(), &poolInfo, nullptr, &pool));
    VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, pool,
                                          VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
    SIXWAY_VK(vkAllocateCommandBuffers(context.device(), &allocInfo, &commands));
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    SIXWAY_VK(vkCreateFence(context.device(), &fenceInfo, nullptr, &fence));
  }
  ~EngineCommands() {
    vkDestroyFence(context.device(), fence, nullptr);
    vkDestroyCommandPool(context.device(), pool, nullptr);
  }
  EngineCommands(const EngineCommands&) = delete;
  EngineCommands& operator=(const EngineCommands&) = delete;
  VkCommandBuffer begin() {
    SIXWAY_VK(vkResetCommandBuffer(commands, 0));
    VkCommandBufferBeginInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    SIXWAY_VK(vkBeginCommandBuffer(commands, &info));
    return commands;
  }
  // Ends, submits and waits.
  void submitAndWait() {
    SIXWAY_VK(vkEndCommandBuffer(commands));
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands;
    SIXWAY_VK(vkResetFences(context.device(), 1, &fence));
    SIXWAY_VK(vkQueueSubmit(context.queue(), 1, &submit, fence));
    SIXWAY_VK(vkWaitForFences(context.device(), 1, &fence, VK_TRUE, UINT64_MAX));
  }

  const gpu::Context& context;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
};

// The engine's path for sixway's one-time work (EngineDevice::submitAndWait), counting the calls.
struct EngineUploads {
  explicit EngineUploads(const gpu::Context& context) : commands(context) {}
  std::function<void(const std::function<void(VkCommandBuffer)>&)> submit() {
    return [this](const std::function<void(VkCommandBuffer)>& record) {
      ++calls;
      record(commands.begin());
      commands.submitAndWait();
    };
  }
  EngineCommands commands;
  int calls = 0;
};

// An "engine" on sixway's own device: the device borrowed through the public API and one command buffer, one
// frame at a time.
struct BorrowingEngine {
  // `submit`: EngineDevice::submitAndWait (unset: sixway submits its one-time work itself).
  explicit BorrowingEngine(const Device& own,
                           std::function<void(const std::function<void(VkCommandBuffer)>&)> submit = {})
      : context(runtime::Access::context(own)),
        features(gpu::DeviceFeatures::toEnable(gpu::DeviceFeatures::supportedBy(context.physicalDevice()))),
        device(engineDevice(context, features, std::move(submit))),
        frame(context) {}
  static Device engineDevice(const gpu::Context& context, gpu::DeviceFeatures& features,
                             std::function<void(const std::function<void(VkCommandBuffer)>&)> submit) {
    const std::vector<const char*> extensions = gpu::requiredDeviceExtensions();
    return Device(EngineDevice{context.instance(),
                               context.physicalDevice(),
                               context.device(),
                               context.queue(),
                               context.queueFamily(),
                               {extensions.begin(), extensions.end()},
                               features.chain(),
                               2,
                               std::move(submit)});
  }
  VkCommandBuffer begin() { return frame.begin(); }
  void submitAndWait() { frame.submitAndWait(); }

  const gpu::Context& context;
  gpu::DeviceFeatures features;
  Device device;
  EngineCommands frame;
};

// `frames` frames of `simulation` and `renderer` into `targets`, cleared to `background` first (the depth
// too, unless `clearDepth` is false), each submitted and waited for.
inline void recordFrames(BorrowingEngine& engine, const EngineTargets& targets, SmokeSimulation& simulation,
                         SmokeRenderer& renderer, const float background[4], bool clearDepth = true,
                         int frames = 3) {
  for (uint64_t frame = 0; frame < uint64_t(frames); ++frame) {
    VkCommandBuffer commands = engine.begin();
    targets.recordClear(commands, background, clearDepth);
    simulation.record(commands, frame);
    renderer.record(commands, frame);
    engine.submitAndWait();
  }
}

inline double psnr(const std::vector<float>& a, const std::vector<float>& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) sum += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
  return sum == 0.0 ? INFINITY : 10.0 * std::log10(double(a.size()) / sum);
}

}  // namespace sixway::test
