#pragma once
// Device memory as buffers and images hold it, and the interface of a caller's sub-allocator.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>

namespace sixway::gpu {

// A block of device memory a buffer or image is bound to: `memory` at `offset`; `mapped` its first byte when
// it was asked mapped; `token` the allocator's own.
struct MemoryBlock {
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize offset = 0;
  void* mapped = nullptr;
  uint64_t token = 0;
};

// A caller's device-memory sub-allocator (ExternalDevice::memory): a block of requirements.size bytes at
// requirements.alignment of memory type `type`, persistently mapped when `map`; memory VK_NULL_HANDLE when it
// has none left. Both functions or neither.
struct MemoryAllocator {
  std::function<MemoryBlock(const VkMemoryRequirements& requirements, uint32_t type, bool map)> allocate;
  std::function<void(const MemoryBlock& block)> free;
};

}  // namespace sixway::gpu
