#pragma once
// The window's swapchain: each frame the display image (DisplayPass) is blitted into the next swapchain
// image, the user interface is drawn over it in one render pass, and the image is presented. Recreated when
// the window's size or the vsync choice changes.
#include <vulkan/vulkan.h>

#include <functional>
#include <optional>
#include <vector>

#include "gpu/buffer.h"
#include "io/image.h"

struct GLFWwindow;

namespace sixway::gpu {
class Context;
class Image;
}  // namespace sixway::gpu

namespace sixway::app::demo {

class Presenter {
 public:
  // Throws std::runtime_error (one line) when the device cannot present to the window.
  Presenter(const gpu::Context& context, GLFWwindow* window, bool vsync);
  ~Presenter();
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  // The swapchain's format (8-bit UNORM preferred, so the display image holds sRGB codes the blit copies).
  VkFormat format() const { return format_; }
  VkExtent2D extent() const { return extent_; }
  VkRenderPass renderPass() const { return renderPass_; }
  uint32_t minImageCount() const { return minImageCount_; }
  uint32_t imageCount() const { return uint32_t(images_.size()); }
  bool vsync() const { return vsync_; }

  // Recreates the swapchain when the window's framebuffer size or `vsync` changed; true when it did.
  bool update(bool vsync);
  // Blits `display` (scaled to the swapchain's extent), records `overlay` inside the render pass, presents.
  // Waits for the previous frame first. False when the swapchain was out of date (recreated; nothing shown).
  bool present(const gpu::Image& display, const std::function<void(VkCommandBuffer)>& overlay);
  // Keeps a copy of the next presented image, with the overlay (the window as the user sees it).
  void requestCapture() { captureRequested_ = true; }
  // The kept copy, RGBA in [0, 1] (sRGB codes / 255), once; none before a capture was presented.
  std::optional<io::Image> takeCapture();

 private:
  void createSwapchain();
  void destroySwapchain(VkSwapchainKHR keep = VK_NULL_HANDLE);
  void recordCapture(VkImage image);

  const gpu::Context& context_;
  GLFWwindow* window_;
  bool vsync_;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkColorSpaceKHR colorSpace_ = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
  VkExtent2D extent_{};
  uint32_t minImageCount_ = 2;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  std::vector<VkImage> images_;
  std::vector<VkImageView> views_;
  std::vector<VkFramebuffer> framebuffers_;
  VkRenderPass renderPass_ = VK_NULL_HANDLE;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer commands_ = VK_NULL_HANDLE;
  VkFence done_ = VK_NULL_HANDLE;
  VkSemaphore acquired_ = VK_NULL_HANDLE, rendered_ = VK_NULL_HANDLE;
  bool captureRequested_ = false;
  std::optional<gpu::Buffer> capture_;  // of the frame in flight, read after its fence
  VkExtent2D captureExtent_{};
  VkFormat captureFormat_ = VK_FORMAT_UNDEFINED;
  bool captureSupported_ = false;
};

}  // namespace sixway::app::demo
