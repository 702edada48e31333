#pragma once
// A VkBuffer with its own memory, zero-filled on creation (unless asked not to). Device buffers are filled
// and read through staging copies; host buffers stay mapped. Frame-parameter buffers are device buffers with
// a host copy that mapped() exposes: a gpu::Sequence writes that whole copy into the command buffer when it
// records a frame (vkCmdUpdateBuffer), so the values a frame sees are the ones set before it was recorded,
// however many frames are in flight (and the device memory needs no clearing).
#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "gpu/memory_block.h"

namespace sixway::gpu {

class Context;

enum class MemoryKind { Device, HostUpload, HostReadback, FrameParameters };

class Buffer {
 public:
  Buffer() = default;
  // `name` appears in errors (e.g. when the size exceeds what the device can bind). Its bytes start as zeros
  // unless `zeroed` is false (for a buffer whose first use writes every byte: no submission to clear it).
  Buffer(const Context& context, uint64_t bytes, VkBufferUsageFlags usage, MemoryKind kind, std::string name,
         bool zeroed = true);
  // A device-local storage buffer that can also be copied to and from.
  static Buffer storage(const Context& context, uint64_t bytes, std::string name, bool zeroed = true);
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;

  VkBuffer handle() const { return buffer_; }
  uint64_t size() const { return size_; }
  const std::string& name() const { return name_; }
  void* mapped() const { return mapped_; }
  MemoryKind kind() const { return kind_; }

  void upload(std::span<const std::byte> data, uint64_t offset = 0);
  void download(std::span<std::byte> data, uint64_t offset = 0) const;

  template <typename T>
  void upload(const std::vector<T>& values) {
    upload(std::as_bytes(std::span(values)));
  }
  template <typename T>
  std::vector<T> download() const {
    std::vector<T> values(size_ / sizeof(T));
    download(std::as_writable_bytes(std::span(values)));
    return values;
  }

 private:
  void release();

  const Context* context_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  MemoryBlock memory_;
  uint64_t size_ = 0;
  void* mapped_ = nullptr;
  MemoryKind kind_ = MemoryKind::Device;
  std::vector<std::byte> hostCopy_;  // FrameParameters: the values of the next recorded frame
  std::string name_;
};

// A view of a buffer as an array of texels of one format, for BindingType::StorageTexelBuffer: shaders read
// it with imageLoad (format conversion by the device) while other dispatches write the same buffer as a
// storage buffer. The buffer needs VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT and must outlive the view.
class BufferView {
 public:
  BufferView() = default;
  BufferView(const Context& context, const Buffer& buffer, VkFormat format);
  ~BufferView();
  BufferView(BufferView&& other) noexcept;
  BufferView& operator=(BufferView&& other) noexcept;

  VkBufferView handle() const { return view_; }
  // The viewed buffer's handle, not its Buffer: a Buffer may move (a FeatureMap holding both moved in a
  // vector), its handle does not; barriers follow the handle.
  VkBuffer bufferHandle() const { return buffer_; }

 private:
  void release();

  const Context* context_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkBufferView view_ = VK_NULL_HANDLE;
};

}  // namespace sixway::gpu
