#include "app/demo/presenter.h"

#include "app/demo/display_pass.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <stdexcept>

#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/image.h"

namespace sixway::app::demo {
namespace {

VkSurfaceFormatKHR chooseFormat(VkPhysicalDevice device, VkSurfaceKHR surface) {
  uint32_t n = 0;
  SIXWAY_VK(vkGetPhysicalDeviceSurfaceFormatsKHR(device, surface, &n, nullptr));
  std::vector<VkSurfaceFormatKHR> formats(n);
  SIXWAY_VK(vkGetPhysicalDeviceSurfaceFormatsKHR(device, surface, &n, formats.data()));
  for (VkFormat wanted :
       {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB})
    for (const VkSurfaceFormatKHR& f : formats)
      if (f.format == wanted && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return f;
  throw std::runtime_error("the window offers no 8-bit RGBA or BGRA surface format");
}

VkPresentModeKHR choosePresentMode(VkPhysicalDevice device, VkSurfaceKHR surface, bool vsync) {
  if (vsync) return VK_PRESENT_MODE_FIFO_KHR;  // always supported
  uint32_t n = 0;
  SIXWAY_VK(vkGetPhysicalDeviceSurfacePresentModesKHR(device, surface, &n, nullptr));
  std::vector<VkPresentModeKHR> modes(n);
  SIXWAY_VK(vkGetPhysicalDeviceSurfacePresentModesKHR(device, surface, &n, modes.data()));
  for (VkPresentModeKHR wanted : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
    if (std::find(modes.begin(), modes.end(), wanted) != modes.end()) return wanted;
  return VK_PRESENT_MODE_FIFO_KHR;
}

}  // namespace

Presenter::Presenter(const gpu::Context& context, GLFWwindow* window, bool vsync)
    : context_(context), window_(window), vsync_(vsync) {
  SIXWAY_VK(glfwCreateWindowSurface(context.instance(), window, nullptr, &surface_));
  VkBool32 supported = VK_FALSE;
  SIXWAY_VK(vkGetPhysicalDeviceSurfaceSupportKHR(context.physicalDevice(), context.queueFamily(), surface_,
                                                 &supported));
  if (!supported) {
    vkDestroySurfaceKHR(context.instance(), surface_, nullptr);
    throw std::runtime_error(std::string("the Vulkan device ") + context.properties().deviceName +
                             " cannot present to this window");
  }
  const VkSurfaceFormatKHR format = chooseFormat(context.physicalDevice(), surface_);
  format_ = format.format;
  colorSpace_ = format.colorSpace;

  // The display image is blitted in (TRANSFER_DST), the interface drawn over it, then presented.
  VkAttachmentDescription attachment{};
  attachment.format = format_;
  attachment.samples = VK_SAMPLE_COUNT_1_BIT;
  attachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  attachment.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  attachment.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  attachment.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  attachment.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  VkAttachmentReference colour{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &colour;
  VkSubpassDependency afterBlit{};
  afterBlit.srcSubpass = VK_SUBPASS_EXTERNAL;
  afterBlit.dstSubpass = 0;
  afterBlit.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  afterBlit.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  afterBlit.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  afterBlit.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  VkRenderPassCreateInfo pass{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  pass.attachmentCount = 1;
  pass.pAttachments = &attachment;
  pass.subpassCount = 1;
  pass.pSubpasses = &subpass;
  pass.dependencyCount = 1;
  pass.pDependencies = &afterBlit;
  SIXWAY_VK(vkCreateRenderPass(context.device(), &pass, nullptr, &renderPass_));

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = context.queueFamily();
  SIXWAY_VK(vkCreateCommandPool(context.device(), &poolInfo, nullptr, &pool_));
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = pool_;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  SIXWAY_VK(vkAllocateCommandBuffers(context.device(), &alloc, &commands_));
  VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  fence.flags = VK_FENCE_CREATE_SIGNALED_BIT;
  SIXWAY_VK(vkCreateFence(context.device(), &fence, nullptr, &done_));
  VkSemaphoreCreateInfo semaphore{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  SIXWAY_VK(vkCreateSemaphore(context.device(), &semaphore, nullptr, &acquired_));
  SIXWAY_VK(vkCreateSemaphore(context.device(), &semaphore, nullptr, &rendered_));
  createSwapchain();
}

Presenter::~Presenter() {
  VkDevice device = context_.device();
  vkDeviceWaitIdle(device);
  destroySwapchain();
  vkDestroySemaphore(device, acquired_, nullptr);
  vkDestroySemaphore(device, rendered_, nullptr);
  vkDestroyFence(device, done_, nullptr);
  vkDestroyCommandPool(device, pool_, nullptr);
  vkDestroyRenderPass(device, renderPass_, nullptr);
  vkDestroySurfaceKHR(context_.instance(), surface_, nullptr);
}

void Presenter::createSwapchain() {
  VkSurfaceCapabilitiesKHR caps{};
  SIXWAY_VK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(context_.physicalDevice(), surface_, &caps));
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  extent_ = caps.currentExtent;
  if (extent_.width == UINT32_MAX)
    extent_ = {std::clamp(uint32_t(width), caps.minImageExtent.width, caps.maxImageExtent.width),
               std::clamp(uint32_t(height), caps.minImageExtent.height, caps.maxImageExtent.height)};
  minImageCount_ = std::max(2u, caps.minImageCount);
  uint32_t count = minImageCount_ + 1;
  if (caps.maxImageCount > 0) count = std::min(count, caps.maxImageCount);

  VkSwapchainKHR old = swapchain_;
  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = surface_;
  info.minImageCount = count;
  info.imageFormat = format_;
  info.imageColorSpace = colorSpace_;
  info.imageExtent = extent_;
  info.imageArrayLayers = 1;
  info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  if (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT)
    info.imageUsage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  captureSupported_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  info.presentMode = choosePresentMode(context_.physicalDevice(), surface_, vsync_);
  info.clipped = VK_TRUE;
  info.oldSwapchain = old;
  SIXWAY_VK(vkCreateSwapchainKHR(context_.device(), &info, nullptr, &swapchain_));
  if (old != VK_NULL_HANDLE)
    destroySwapchain(swapchain_), vkDestroySwapchainKHR(context_.device(), old, nullptr);

  uint32_t n = 0;
  SIXWAY_VK(vkGetSwapchainImagesKHR(context_.device(), swapchain_, &n, nullptr));
  images_.resize(n);
  SIXWAY_VK(vkGetSwapchainImagesKHR(context_.device(), swapchain_, &n, images_.data()));
  for (VkImage image : images_) {
    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = image;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = format_;
    view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView v = VK_NULL_HANDLE;
    SIXWAY_VK(vkCreateImageView(context_.device(), &view, nullptr, &v));
    views_.push_back(v);
    VkFramebufferCreateInfo fb{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fb.renderPass = renderPass_;
    fb.attachmentCount = 1;
    fb.pAttachments = &v;
    fb.width = extent_.width;
    fb.height = extent_.height;
    fb.layers = 1;
    VkFramebuffer f = VK_NULL_HANDLE;
    SIXWAY_VK(vkCreateFramebuffer(context_.device(), &fb, nullptr, &f));
    framebuffers_.push_back(f);
  }
}

// Destroys the views and framebuffers, and the swapchain unless it is `keep` (the one that replaces it).
void Presenter::destroySwapchain(VkSwapchainKHR keep) {
  VkDevice device = context_.device();
  for (VkFramebuffer f : framebuffers_) vkDestroyFramebuffer(device, f, nullptr);
  for (VkImageView v : views_) vkDestroyImageView(device, v, nullptr);
  framebuffers_.clear();
  views_.clear();
  images_.clear();
  if (swapchain_ != keep) {
    vkDestroySwapchainKHR(device, swapchain_, nullptr);
    swapchain_ = VK_NULL_HANDLE;
  }
}

bool Presenter::update(bool vsync) {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  if (width == 0 || height == 0) return false;  // minimized: keep what there is
  if (vsync == vsync_ && uint32_t(width) == extent_.width && uint32_t(height) == extent_.height) return false;
  vsync_ = vsync;
  SIXWAY_VK(vkDeviceWaitIdle(context_.device()));
  createSwapchain();
  return true;
}

// Copies the swapchain image (in PRESENT_SRC after the render pass) into a host buffer before it is
// presented.
void Presenter::recordCapture(VkImage image) {
  captureRequested_ = false;
  if (!captureSupported_) throw std::runtime_error("this window's swapchain images cannot be copied from");
  capture_.emplace(context_, uint64_t(extent_.width) * extent_.height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                   gpu::MemoryKind::HostReadback, "window capture");
  captureExtent_ = extent_;
  captureFormat_ = format_;
  VkImageMemoryBarrier toSource{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  toSource.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  toSource.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  toSource.oldLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  toSource.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  toSource.srcQueueFamilyIndex = toSource.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  toSource.image = image;
  toSource.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(commands_, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &toSource);
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {extent_.width, extent_.height, 1};
  vkCmdCopyImageToBuffer(commands_, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, capture_->handle(), 1,
                         &copy);
  VkImageMemoryBarrier back = toSource;
  back.srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  back.dstAccessMask = 0;
  back.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  back.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  vkCmdPipelineBarrier(commands_, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0, 0,
                       nullptr, 0, nullptr, 1, &back);
}

std::optional<io::Image> Presenter::takeCapture() {
  if (!capture_) return std::nullopt;
  SIXWAY_VK(vkWaitForFences(context_.device(), 1, &done_, VK_TRUE, UINT64_MAX));
  io::Image out = imageFromDisplayTexels(capture_->download<uint8_t>(), captureExtent_.width,
                                         captureExtent_.height, captureFormat_);
  capture_.reset();
  return out;
}

bool Presenter::present(const gpu::Image& display, const std::function<void(VkCommandBuffer)>& overlay) {
  VkDevice device = context_.device();
  SIXWAY_VK(vkWaitForFences(device, 1, &done_, VK_TRUE, UINT64_MAX));
  uint32_t index = 0;
  VkResult acquired =
      vkAcquireNextImageKHR(device, swapchain_, UINT64_MAX, acquired_, VK_NULL_HANDLE, &index);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
    SIXWAY_VK(vkDeviceWaitIdle(device));
    createSwapchain();
    return false;
  }
  if (acquired != VK_SUBOPTIMAL_KHR) SIXWAY_VK(acquired);
  SIXWAY_VK(vkResetFences(device, 1, &done_));

  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  SIXWAY_VK(vkResetCommandBuffer(commands_, 0));
  SIXWAY_VK(vkBeginCommandBuffer(commands_, &begin));
  // The display image was drawn by an earlier submission: its writes before the blit's reads.
  VkMemoryBarrier written{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  written.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  written.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  VkImageMemoryBarrier toTransfer{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  toTransfer.srcAccessMask = 0;
  toTransfer.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toTransfer.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  toTransfer.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  toTransfer.srcQueueFamilyIndex = toTransfer.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  toTransfer.image = images_[index];
  toTransfer.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(commands_,
                       VK_PIPELINE_STAGE_ALL_COMMANDS_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &written, 0, nullptr, 1, &toTransfer);
  VkImageBlit blit{};
  blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {int32_t(display.desc().width), int32_t(display.desc().height), 1};
  blit.dstOffsets[1] = {int32_t(extent_.width), int32_t(extent_.height), 1};
  vkCmdBlitImage(commands_, display.handle(), VK_IMAGE_LAYOUT_GENERAL, images_[index],
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);

  VkRenderPassBeginInfo pass{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  pass.renderPass = renderPass_;
  pass.framebuffer = framebuffers_[index];
  pass.renderArea = {{0, 0}, extent_};
  vkCmdBeginRenderPass(commands_, &pass, VK_SUBPASS_CONTENTS_INLINE);
  overlay(commands_);
  vkCmdEndRenderPass(commands_);
  if (captureRequested_) recordCapture(images_[index]);
  SIXWAY_VK(vkEndCommandBuffer(commands_));

  const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.waitSemaphoreCount = 1;
  submit.pWaitSemaphores = &acquired_;
  submit.pWaitDstStageMask = &waitStage;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands_;
  submit.signalSemaphoreCount = 1;
  submit.pSignalSemaphores = &rendered_;
  SIXWAY_VK(vkQueueSubmit(context_.queue(), 1, &submit, done_));

  VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  present.waitSemaphoreCount = 1;
  present.pWaitSemaphores = &rendered_;
  present.swapchainCount = 1;
  present.pSwapchains = &swapchain_;
  present.pImageIndices = &index;
  const VkResult presented = vkQueuePresentKHR(context_.queue(), &present);
  if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR ||
      acquired == VK_SUBOPTIMAL_KHR) {
    SIXWAY_VK(vkDeviceWaitIdle(device));
    createSwapchain();
    return false;
  }
  SIXWAY_VK(presented);
  return true;
}

}  // namespace sixway::app::demo
