#pragma once
// A 2D or 3D VkImage with its view, kept in VK_IMAGE_LAYOUT_GENERAL for its whole life: every
// stage reads and writes it as storage, samples it, or renders to it without layout changes.
#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "gpu/memory_block.h"

namespace sixway::gpu {

class Context;

struct ImageDesc {
  uint32_t width = 1, height = 1, depth = 1;  // depth > 1 makes a 3D image
  VkFormat format = VK_FORMAT_R32G32B32A32_SFLOAT;
  VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  std::string name;
};

class Image {
 public:
  Image() = default;
  Image(const Context& context, const ImageDesc& desc);
  // An image and view the caller owns (an engine's render target, kept in VK_IMAGE_LAYOUT_GENERAL while
  // sixway uses it): nothing is created or destroyed.
  static Image borrowed(const Context& context, VkImage image, VkImageView view, const ImageDesc& desc);
  ~Image();
  Image(Image&& other) noexcept;
  Image& operator=(Image&& other) noexcept;

  VkImage handle() const { return image_; }
  VkImageView view() const { return view_; }
  const ImageDesc& desc() const { return desc_; }
  uint64_t byteSize() const;

  // Tightly packed texels, row-major, row 0 first, slice after slice.
  void upload(std::span<const std::byte> texels);
  void download(std::span<std::byte> texels) const;
  template <typename T>
  std::vector<T> download() const {
    std::vector<T> values(byteSize() / sizeof(T));
    download(std::as_writable_bytes(std::span(values)));
    return values;
  }

 private:
  void release();

  const Context* context_ = nullptr;
  ImageDesc desc_;
  VkImage image_ = VK_NULL_HANDLE;
  MemoryBlock memory_;
  VkImageView view_ = VK_NULL_HANDLE;
  bool owned_ = true;
};

// Records a barrier that moves mip level 0, array layer 0 of `image` (every aspect of `format`) from layout
// `from` to `to`, after every earlier command's writes and before every later command's accesses.
void recordLayoutChange(VkCommandBuffer commands, VkImage image, VkFormat format, VkImageLayout from,
                        VkImageLayout to);

uint32_t bytesPerTexel(VkFormat format);
// The depth formats sixway samples (D16, D24, D32, with or without stencil); their views and copies take
// the depth aspect.
bool isDepthFormat(VkFormat format);
bool hasStencil(VkFormat format);

// A sampler for normalised coordinates, clamped to the edge.
class Sampler {
 public:
  Sampler(const Context& context, VkFilter filter);
  ~Sampler();
  Sampler(const Sampler&) = delete;
  Sampler& operator=(const Sampler&) = delete;
  VkSampler handle() const { return sampler_; }

 private:
  const Context* context_;
  VkSampler sampler_ = VK_NULL_HANDLE;
};

}  // namespace sixway::gpu
