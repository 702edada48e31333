#include "gpu/buffer.h"

#include <cstring>
#include <utility>

#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/one_shot.h"
#include "gpu/vulkan_functions.h"

namespace sixway::gpu {

Buffer::Buffer(const Context& context, uint64_t bytes, VkBufferUsageFlags usage, MemoryKind kind,
               std::string name, bool zeroed)
    : context_(&context), size_(bytes), kind_(kind), name_(std::move(name)) {
  if (bytes == 0) throw GpuError(name_ + ": a buffer cannot be empty");
  if (kind == MemoryKind::FrameParameters) {
    if (bytes % 4 != 0) throw GpuError(name_ + ": frame parameters are whole 32-bit words");
    usage |= VK_BUFFER_USAGE_TRANSFER_DST_BIT;  // written by vkCmdUpdateBuffer
  }
  if (usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) context.requireStorageBufferFits(bytes, name_);
  if (bytes > context.capabilities().deviceLocalHeapBytes)  // staging and uniform buffers too
    throw LimitError(name_ + " needs " + formatBytes(bytes) + ", more than the device's " +
                     formatBytes(context.capabilities().deviceLocalHeapBytes) + " of memory");

  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = bytes;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  SIXWAY_VK(vkCreateBuffer(context.device(), &info, context.allocator(), &buffer_));

  // Past this point the buffer owns what it made: a failure releases it (the destructor does not run).
  try {
    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(context.device(), buffer_, &requirements);
    VkMemoryPropertyFlags properties = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    if (kind == MemoryKind::HostUpload)
      properties = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    if (kind == MemoryKind::HostReadback)
      properties = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT |
                   VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
    uint32_t type = 0;
    try {
      type = context.findMemoryType(requirements.memoryTypeBits, properties);
    } catch (const GpuError&) {  // cached host memory is a preference, coherent host memory a must
      if (kind != MemoryKind::HostReadback) throw;
      type = context.findMemoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                                     VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    }
    const bool host = kind == MemoryKind::HostUpload || kind == MemoryKind::HostReadback;
    memory_ = context.allocateMemory(requirements, type, host, name_);
    context.countAllocation(int64_t(bytes));
    SIXWAY_VK(vkBindBufferMemory(context.device(), buffer_, memory_.memory, memory_.offset));
    // New memory holds whatever was there before (after a free: another run's data, even NaN), so
    // every buffer starts as zeros. Frame parameters need no fill: each recorded frame writes the whole
    // buffer before its work reads it (Sequence::recordInto, recordParameterUpdates).
    if (kind == MemoryKind::FrameParameters) {
      hostCopy_.assign(bytes, std::byte{0});
      mapped_ = hostCopy_.data();
    } else if (host) {
      mapped_ = memory_.mapped;
      std::memset(mapped_, 0, bytes);
    } else if (zeroed && (usage & VK_BUFFER_USAGE_TRANSFER_DST_BIT)) {
      submitOnce(context, [&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, buffer_, 0, VK_WHOLE_SIZE, 0); });
    }
  } catch (...) {
    release();
    throw;
  }
}

Buffer Buffer::storage(const Context& context, uint64_t bytes, std::string name, bool zeroed) {
  return Buffer(context, bytes,
                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                    VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                MemoryKind::Device, std::move(name), zeroed);
}

Buffer::~Buffer() {
  release();
}

Buffer::Buffer(Buffer&& other) noexcept {
  *this = std::move(other);
}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, MemoryBlock{});
    size_ = std::exchange(other.size_, 0);
    mapped_ = std::exchange(other.mapped_, nullptr);
    kind_ = other.kind_;
    hostCopy_ = std::move(other.hostCopy_);  // keeps its storage, so mapped_ stays valid
    name_ = std::move(other.name_);
  }
  return *this;
}

void Buffer::release() {
  if (!context_) return;
  if (buffer_) vkDestroyBuffer(context_->device(), buffer_, context_->allocator());
  if (memory_.memory) {
    context_->freeMemory(memory_);
    context_->countAllocation(-int64_t(size_));
  }
  buffer_ = VK_NULL_HANDLE;
  memory_ = {};
  mapped_ = nullptr;
}

void Buffer::upload(std::span<const std::byte> data, uint64_t offset) {
  if (offset + data.size() > size_)
    throw GpuError(name_ + ": upload of " + std::to_string(data.size()) + " bytes at offset " +
                   std::to_string(offset) + " exceeds its " + std::to_string(size_) + " bytes");
  if (data.empty()) return;
  if (mapped_) {
    std::memcpy(static_cast<std::byte*>(mapped_) + offset, data.data(), data.size());
    return;
  }
  Buffer staging(*context_, data.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryKind::HostUpload,
                 name_ + " (staging)");
  std::memcpy(staging.mapped(), data.data(), data.size());
  submitOnce(*context_, [&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, offset, data.size()};
    vkCmdCopyBuffer(cmd, staging.handle(), buffer_, 1, &region);
  });
}

void Buffer::download(std::span<std::byte> data, uint64_t offset) const {
  if (offset + data.size() > size_)
    throw GpuError(name_ + ": download of " + std::to_string(data.size()) + " bytes at offset " +
                   std::to_string(offset) + " exceeds its " + std::to_string(size_) + " bytes");
  if (data.empty()) return;
  if (mapped_) {
    std::memcpy(data.data(), static_cast<const std::byte*>(mapped_) + offset, data.size());
    return;
  }
  Buffer staging(*context_, data.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryKind::HostReadback,
                 name_ + " (readback)");
  submitOnce(*context_, [&](VkCommandBuffer cmd) {
    VkBufferCopy region{offset, 0, data.size()};
    vkCmdCopyBuffer(cmd, buffer_, staging.handle(), 1, &region);
  });
  std::memcpy(data.data(), staging.mapped(), data.size());
}

BufferView::BufferView(const Context& context, const Buffer& buffer, VkFormat format)
    : context_(&context), buffer_(buffer.handle()) {
  VkBufferViewCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
  info.buffer = buffer.handle();
  info.format = format;
  info.range = VK_WHOLE_SIZE;
  SIXWAY_VK(vkCreateBufferView(context.device(), &info, context.allocator(), &view_));
}

BufferView::~BufferView() {
  release();
}

BufferView::BufferView(BufferView&& other) noexcept {
  *this = std::move(other);
}

BufferView& BufferView::operator=(BufferView&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    view_ = std::exchange(other.view_, VK_NULL_HANDLE);
  }
  return *this;
}

void BufferView::release() {
  if (context_ && view_) vkDestroyBufferView(context_->device(), view_, context_->allocator());
  view_ = VK_NULL_HANDLE;
}

}  // namespace sixway::gpu
