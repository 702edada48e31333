#include "gpu/image.h"

#include <cstring>
#include <utility>

#include "gpu/buffer.h"
#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/one_shot.h"
#include "gpu/vulkan_functions.h"

namespace sixway::gpu {

uint32_t bytesPerTexel(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_R16G16_SFLOAT:
      return 4;
    case VK_FORMAT_X8_D24_UNORM_PACK32:
    case VK_FORMAT_D24_UNORM_S8_UINT:   // the depth aspect, as buffer copies hold it
    case VK_FORMAT_D32_SFLOAT_S8_UINT:  // the same
      return 4;
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_D16_UNORM:
      return 2;
    case VK_FORMAT_R8_UNORM:
      return 1;
    case VK_FORMAT_R32G32_SFLOAT:
    case VK_FORMAT_R16G16B16A16_SFLOAT:
      return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      return 16;
    default:
      throw GpuError("image format " + std::to_string(format) + " is not used by sixway");
  }
}

bool isDepthFormat(VkFormat format) {
  switch (format) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
      return true;
    default:
      return false;
  }
}

bool hasStencil(VkFormat format) {
  return format == VK_FORMAT_D24_UNORM_S8_UINT || format == VK_FORMAT_D32_SFLOAT_S8_UINT;
}

Image::Image(const Context& context, const ImageDesc& desc) : context_(&context), desc_(desc) {
  const VkPhysicalDeviceLimits& limits = context.limits();
  const bool is3d = desc.depth > 1;
  const uint32_t maxSide = is3d ? limits.maxImageDimension3D : limits.maxImageDimension2D;
  if (desc.width == 0 || desc.height == 0 || desc.depth == 0 || desc.width > maxSide ||
      desc.height > maxSide || desc.depth > maxSide)
    throw LimitError(desc.name + ": image of " + std::to_string(desc.width) + "x" +
                     std::to_string(desc.height) + (is3d ? "x" + std::to_string(desc.depth) : "") +
                     " is outside the device's 1.." + std::to_string(maxSide) + " per side");
  if (byteSize() > context.capabilities().deviceLocalHeapBytes)
    throw LimitError(desc.name + ": image of " + formatBytes(byteSize()) + " is more than the device's " +
                     formatBytes(context.capabilities().deviceLocalHeapBytes) + " of memory");

  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = is3d ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
  info.format = desc.format;
  info.extent = {desc.width, desc.height, desc.depth};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = desc.usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  SIXWAY_VK(vkCreateImage(context.device(), &info, context.allocator(), &image_));

  // Past this point the image owns what it made: a failure releases it (the destructor does not run).
  try {
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(context.device(), image_, &requirements);
    memory_ = context.allocateMemory(
        requirements,
        context.findMemoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT), false,
        desc.name);
    context.countAllocation(int64_t(byteSize()));
    SIXWAY_VK(vkBindImageMemory(context.device(), image_, memory_.memory, memory_.offset));

    const VkImageAspectFlags aspect =
        isDepthFormat(desc.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = image_;
    viewInfo.viewType = is3d ? VK_IMAGE_VIEW_TYPE_3D : VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = desc.format;
    viewInfo.subresourceRange = {aspect, 0, 1, 0, 1};
    SIXWAY_VK(vkCreateImageView(context.device(), &viewInfo, context.allocator(), &view_));

    submitOnce(context, [&](VkCommandBuffer cmd) {
      recordLayoutChange(cmd, image_, desc.format, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    });
  } catch (...) {
    release();
    throw;
  }
}

void recordLayoutChange(VkCommandBuffer commands, VkImage image, VkFormat format, VkImageLayout from,
                        VkImageLayout to) {
  VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  barrier.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  barrier.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  barrier.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  barrier.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  barrier.oldLayout = from;
  barrier.newLayout = to;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {
      VkImageAspectFlags(isDepthFormat(format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT), 0, 1,
      0, 1};
  if (hasStencil(format)) barrier.subresourceRange.aspectMask |= VK_IMAGE_ASPECT_STENCIL_BIT;
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(commands, &dependency);
}

Image::~Image() {
  release();
}

Image::Image(Image&& other) noexcept {
  *this = std::move(other);
}

Image& Image::operator=(Image&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    desc_ = std::move(other.desc_);
    image_ = std::exchange(other.image_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, MemoryBlock{});
    view_ = std::exchange(other.view_, VK_NULL_HANDLE);
    owned_ = std::exchange(other.owned_, true);
  }
  return *this;
}

Image Image::borrowed(const Context& context, VkImage image, VkImageView view, const ImageDesc& desc) {
  Image borrowed;
  borrowed.context_ = &context;
  borrowed.desc_ = desc;
  borrowed.image_ = image;
  borrowed.view_ = view;
  borrowed.owned_ = false;
  return borrowed;
}

void Image::release() {
  if (!context_ || !owned_) return;
  if (view_) vkDestroyImageView(context_->device(), view_, context_->allocator());
  if (image_) vkDestroyImage(context_->device(), image_, context_->allocator());
  if (memory_.memory) {
    context_->freeMemory(memory_);
    context_->countAllocation(-int64_t(byteSize()));
  }
  view_ = VK_NULL_HANDLE;
  image_ = VK_NULL_HANDLE;
  memory_ = {};
}

uint64_t Image::byteSize() const {
  return uint64_t(desc_.width) * desc_.height * desc_.depth * bytesPerTexel(desc_.format);
}

namespace {

VkBufferImageCopy wholeImage(const ImageDesc& desc) {
  VkBufferImageCopy region{};
  region.imageSubresource = {
      isDepthFormat(desc.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {desc.width, desc.height, desc.depth};
  return region;
}

}  // namespace

void Image::upload(std::span<const std::byte> texels) {
  if (texels.size() != byteSize())
    throw GpuError(desc_.name + ": upload of " + std::to_string(texels.size()) + " bytes, the image holds " +
                   std::to_string(byteSize()));
  Buffer staging(*context_, byteSize(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryKind::HostUpload,
                 desc_.name + " (staging)");
  std::memcpy(staging.mapped(), texels.data(), texels.size());
  submitOnce(*context_, [&](VkCommandBuffer cmd) {
    VkBufferImageCopy region = wholeImage(desc_);
    recordFullBarrier(cmd);
    vkCmdCopyBufferToImage(cmd, staging.handle(), image_, VK_IMAGE_LAYOUT_GENERAL, 1, &region);
    recordFullBarrier(cmd);
  });
}

void Image::download(std::span<std::byte> texels) const {
  if (texels.size() != byteSize())
    throw GpuError(desc_.name + ": download of " + std::to_string(texels.size()) +
                   " bytes, the image holds " + std::to_string(byteSize()));
  Buffer staging(*context_, byteSize(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryKind::HostReadback,
                 desc_.name + " (readback)");
  submitOnce(*context_, [&](VkCommandBuffer cmd) {
    VkBufferImageCopy region = wholeImage(desc_);
    recordFullBarrier(cmd);
    vkCmdCopyImageToBuffer(cmd, image_, VK_IMAGE_LAYOUT_GENERAL, staging.handle(), 1, &region);
    recordFullBarrier(cmd);
  });
  std::memcpy(texels.data(), staging.mapped(), texels.size());
}

Sampler::Sampler(const Context& context, VkFilter filter) : context_(&context) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = filter;
  info.minFilter = filter;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.maxLod = 0.0f;
  SIXWAY_VK(vkCreateSampler(context.device(), &info, context.allocator(), &sampler_));
}

Sampler::~Sampler() {
  vkDestroySampler(context_->device(), sampler_, context_->allocator());
}

}  // namespace sixway::gpu
