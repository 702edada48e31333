#pragma once
// The Vulkan device sixway runs on: one it creates itself (headless, for tools and tests), or an engine's,
// which sixway borrows (docs/embedding.md, "The device").
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sixway {

namespace runtime {
struct Access;
}  // namespace runtime

// sixway's own device.
struct DeviceOptions {
  bool validate = false;     // the Khronos validation layer; every message is counted
  std::optional<int> index;  // a physical device index (as `sixway info` lists them); else the best one
};

// A block of device memory from the engine's allocator: sixway binds a buffer or image to `memory` at
// `offset`; `mapped`, when sixway asked for a mapped block, is the block's first byte in host memory (mapped
// for the block's life); `token` is the engine's own.
struct MemoryBlock {
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize offset = 0;
  void* mapped = nullptr;
  uint64_t token = 0;
};

// The engine's device-memory sub-allocator, for every buffer and image sixway makes. `allocate`: a block of
// requirements.size bytes at a multiple of requirements.alignment, of memory type `type` (one of
// requirements.memoryTypeBits, chosen by sixway: device-local, or host-visible and coherent for uploads and
// readbacks), mapped when `map`; memory VK_NULL_HANDLE when it has none left (sixway throws its LimitError,
// naming what it was making). `free`: the block back, once the GPU is done with it. Both or neither. Blocks
// of buffers and of images (optimal tiling) in one VkDeviceMemory keep bufferImageGranularity apart.
struct DeviceMemoryAllocator {
  std::function<MemoryBlock(const VkMemoryRequirements& requirements, uint32_t type, bool map)> allocate;
  std::function<void(const MemoryBlock& block)> free;
};

// An engine's device. sixway destroys nothing of it. The device must have been created with
// DeviceRequirements' extensions and features (a missing one is an Error naming it), and the queue must do
// graphics and compute. The engine promises that when it records frame n, frame n − framesInFlight has
// completed on the GPU (the usual fence wait before reusing a frame's command buffer).
struct EngineDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  std::vector<std::string> enabledExtensions;  // as given to vkCreateDevice
  const void* enabledFeatures = nullptr;       // the VkPhysicalDeviceFeatures2 chain given to vkCreateDevice
  uint32_t framesInFlight = 2;                 // 1..8
  // Where sixway's one-time work goes (uploads and first layouts, while objects are made and when the first
  // frame of a volume is recorded): the engine records it by calling `record` on a primary command buffer
  // of its own, submits it and waits for it, on the queue and thread it chooses. Unset: sixway submits to
  // `queue` itself and waits on a fence (hostWaits()). Never called for a frame's own work.
  std::function<void(const std::function<void(VkCommandBuffer)>& record)> submitAndWait;
  // Host memory callbacks for every Vulkan object sixway creates and destroys on the device (buffers,
  // images, memory, views, samplers, pipelines, command pools, fences, query pools); null: the driver's.
  const VkAllocationCallbacks* allocator = nullptr;
  // The engine's pipeline cache: sixway creates its pipelines through it and reads or writes no cache file
  // (the engine saves it with its own). Null: sixway's own cache in $XDG_CACHE_HOME/sixway.
  VkPipelineCache pipelineCache = VK_NULL_HANDLE;
  // Where sixway's notes go, one line each without a newline (e.g. a pipeline cache file it could not read or
  // write); unset: stderr. Errors are thrown, never logged.
  std::function<void(const std::string& line)> log;
  // Where buffers and images get their memory; unset: one vkAllocateMemory each.
  DeviceMemoryAllocator memory;
  // The engine's vkGetInstanceProcAddr (its loader, or a layer of its own in front of it): while this device
  // lives, every Vulkan function sixway calls comes from it, process-wide, taken for `instance` (of the first
  // such device, when several with the same one live) (docs/embedding.md, "The device"). Null: the Vulkan
  // loader sixway links. An Error names a function it does not give.
  PFN_vkGetInstanceProcAddr getInstanceProcAddr = nullptr;
};

// What an engine enables on its device for sixway: Vulkan 1.3 with synchronization2, dynamicRendering and
// maintenance4, float atomic add on storage buffers, push descriptors; and the optional features sixway uses
// where the device has them (16-bit storage, fp16 arithmetic, 64-bit integers, the Vulkan memory model with
// its device scope, and VK_NV_cooperative_matrix: the network's convolutions on tensor cores).
class DeviceRequirements {
 public:
  explicit DeviceRequirements(VkPhysicalDevice physicalDevice);
  ~DeviceRequirements();
  DeviceRequirements(const DeviceRequirements&) = delete;
  DeviceRequirements& operator=(const DeviceRequirements&) = delete;

  const std::vector<const char*>& extensions() const;
  // A VkPhysicalDeviceFeatures2 chain (with the 1.1, 1.2, 1.3 and float-atomic structures) to pass as
  // VkDeviceCreateInfo::pNext when the engine has none; valid while this object lives.
  VkPhysicalDeviceFeatures2* features();
  // Merges what sixway needs into the engine's own `info` before vkCreateDevice: each feature switched on in
  // the structure of its chain that holds it (its VkPhysicalDeviceFeatures2 or pEnabledFeatures, a 1.1-1.3
  // aggregate, or the promoted feature's own structure), the rest added as the promoted features' own
  // structures, no sType twice; the extensions added to `extensions`, which `info` then names. The engine's
  // structures must be writable; the added ones live as long as this object (one merge per object).
  void mergeInto(VkDeviceCreateInfo& info, std::vector<const char*>& extensions);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class Device {
 public:
  explicit Device(const DeviceOptions& options = {});
  explicit Device(const EngineDevice& engine);
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  std::string name() const;
  // How often sixway has blocked the host on the GPU (fences, idle waits) since the device was made: the
  // real-time path recorded into an engine's command buffers adds none.
  uint64_t hostWaits() const;
  // Validation messages seen on sixway's own device with DeviceOptions::validate (0 otherwise).
  uint32_t validationMessages() const;
  // Device memory sixway holds now (buffers and images it allocated): flat from the first frames on.
  struct MemoryUse {
    uint64_t allocations = 0, bytes = 0;
  };
  MemoryUse memoryUse() const;

 private:
  friend runtime::Access;  // sixway's own tools (src/runtime/internal.h, not installed)
  struct Impl;
  explicit Device(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace sixway
