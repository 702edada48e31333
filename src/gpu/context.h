#pragma once
// The Vulkan instance, the chosen physical device, the logical device and its one queue.
// Headless by default; pass the window system's instance extensions (GLFW) to present.
#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "gpu/cooperative_matrix.h"
#include "gpu/memory_block.h"
#include "gpu/vulkan_functions.h"

namespace sixway::gpu {

struct ContextOptions {
  bool validate = false;                        // Khronos validation layer; every message is counted
  std::optional<int> deviceIndex;               // --device N; otherwise SIXWAY_DEVICE, then the best device
  std::vector<std::string> instanceExtensions;  // e.g. from glfwGetRequiredInstanceExtensions
  bool presentation = false;                    // enable VK_KHR_swapchain on the device
};

// A device the caller created and owns (an engine's): sixway borrows it, checks that it has the extensions
// and features sixway needs (gpu/device_features.h) and destroys nothing.
struct ExternalDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;  // of queueFamily, with graphics and compute
  uint32_t queueFamily = 0;
  std::vector<std::string> enabledExtensions;  // as passed to vkCreateDevice
  const void* enabledFeatures = nullptr;       // the VkPhysicalDeviceFeatures2 chain passed to vkCreateDevice
  // Frames the caller has in flight: when it records frame n, frame n − framesInFlight has completed.
  uint32_t framesInFlight = 2;
  // Where one-time work (uploads, first layouts: submitOnce) goes: the caller records it with the function
  // given into a primary command buffer of its own, submits and waits. Unset: sixway submits to `queue` and
  // waits on a fence of its own (a host wait).
  std::function<void(const std::function<void(VkCommandBuffer)>&)> submitAndWait;
  // Host memory callbacks for every object sixway creates on the device; null: the driver's.
  const VkAllocationCallbacks* allocator = nullptr;
  // The caller's pipeline cache for sixway's pipelines (PipelineCache borrows it); null: sixway's own.
  VkPipelineCache pipelineCache = VK_NULL_HANDLE;
  // Where notes go (Context::note); unset: stderr.
  std::function<void(const std::string&)> log;
  // Where buffers and images get their memory; unset: one vkAllocateMemory each.
  MemoryAllocator memory;
  // Where sixway's Vulkan functions come from (gpu/vulkan_functions.h) while this device is in use; null: the
  // linked loader.
  PFN_vkGetInstanceProcAddr getInstanceProcAddr = nullptr;
};

// What the stages need to know about the device to size their work.
struct DeviceCapabilities {
  bool shaderFloat16 = false;     // fp16 arithmetic in shaders
  bool storage16Bit = false;      // 16-bit values in storage buffers
  bool timestamps = false;        // timestamps on the compute/graphics queue
  bool independentBlend = false;  // blend states that differ per colour attachment
  double timestampPeriodNs = 1.0;
  uint32_t timestampValidBits = 64;
  uint32_t subgroupSize = 1;
  uint64_t deviceLocalHeapBytes = 0;
  // Enabled cooperative matrices (gpu/cooperative_matrix.h), or none.
  MatrixShape cooperativeMatrix;
};

// The device memory of our live gpu::Buffer and gpu::Image objects (their requested sizes), for long-run
// checks.
struct MemoryUse {
  uint64_t allocations = 0;
  uint64_t bytes = 0;
};

// Counts the messages of the validation layer (and prints them, prefixed "validation:").
class ValidationLog {
 public:
  void add(const char* message);
  uint32_t count() const { return count_.load(); }
  std::vector<std::string> messages() const;
  void clear();

 private:
  std::atomic<uint32_t> count_{0};
  mutable std::mutex mutex_;
  std::vector<std::string> messages_;
};

class Context {
 public:
  explicit Context(const ContextOptions& options = {});
  // Throws GpuError naming what the device lacks (a Vulkan version, an extension, a feature).
  explicit Context(const ExternalDevice& device);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queueFamily() const { return queueFamily_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  const VkPhysicalDeviceLimits& limits() const { return properties_.limits; }
  const VkPhysicalDeviceDriverProperties& driver() const { return driver_; }
  const DeviceCapabilities& capabilities() const { return capabilities_; }
  bool validationEnabled() const { return validation_ != nullptr; }
  // Messages seen so far (zero when validation is off).
  uint32_t validationMessageCount() const { return validation_ ? validation_->count() : 0; }
  ValidationLog* validationLog() const { return validation_.get(); }

  // VK_KHR_push_descriptor entry point: every dispatch pushes its bindings, so no descriptor pools.
  PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;

  uint32_t findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required) const;
  // A block for `requirements` of memory type `type` (ExternalDevice::memory's, or one vkAllocateMemory),
  // mapped when `map`; LimitError naming `what` when the memory is exhausted.
  MemoryBlock allocateMemory(const VkMemoryRequirements& requirements, uint32_t type, bool map,
                             const std::string& what) const;
  void freeMemory(const MemoryBlock& block) const;
  MemoryUse memoryUse() const { return {uint64_t(liveAllocations_.load()), uint64_t(liveBytes_.load())}; }
  // Buffer and Image call this with +bytes when they allocate and −bytes when they free.
  void countAllocation(int64_t bytes) const {
    liveAllocations_ += bytes >= 0 ? 1 : -1;
    liveBytes_ += bytes;
  }
  // Every place the host blocks on the GPU (a fence, an idle queue, a query result) counts itself here, so
  // tests can check that the real-time path records without blocking.
  void countHostWait() const { ++hostWaits_; }
  // When frame n is recorded, frame n − framesInFlight() has completed (1 on sixway's own device, which
  // waits for each submission).
  uint32_t framesInFlight() const { return framesInFlight_; }
  uint64_t hostWaits() const { return hostWaits_.load(); }
  // ExternalDevice::submitAndWait, or empty.
  const std::function<void(const std::function<void(VkCommandBuffer)>&)>& externalSubmit() const {
    return externalSubmit_;
  }

  // ExternalDevice::allocator: pass it to every vkCreate*, vkAllocateMemory, vkDestroy* and vkFreeMemory.
  const VkAllocationCallbacks* allocator() const { return allocator_; }
  // ExternalDevice::pipelineCache, or null.
  VkPipelineCache externalPipelineCache() const { return externalPipelineCache_; }
  // A line for the user that is not an error (e.g. a pipeline cache file left unread): to the caller's log
  // (ExternalDevice::log), else stderr as "sixway: note: <line>".
  void note(const std::string& line) const;
  // Throws a LimitError naming `what` when a storage buffer of `bytes` cannot be bound or held.
  void requireStorageBufferFits(uint64_t bytes, const std::string& what) const;

 private:
  void createInstance(const ContextOptions& options);
  // Destroys what this context created (nothing for an external device); safe to call twice.
  void release();
  void pickPhysicalDevice(const ContextOptions& options);
  void readProperties();
  void createDevice(const ContextOptions& options);

  std::unique_ptr<ValidationLog> validation_;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceDriverProperties driver_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  DeviceCapabilities capabilities_{};
  bool ownsDevice_ = true;
  uint32_t framesInFlight_ = 1;
  mutable std::atomic<int64_t> liveAllocations_{0}, liveBytes_{0};
  mutable std::atomic<uint64_t> hostWaits_{0};
  std::function<void(const std::function<void(VkCommandBuffer)>&)> externalSubmit_;
  const VkAllocationCallbacks* allocator_ = nullptr;
  VkPipelineCache externalPipelineCache_ = VK_NULL_HANDLE;
  std::function<void(const std::string&)> log_;
  MemoryAllocator memoryAllocator_;
  std::unique_ptr<EngineVulkanFunctions> engineFunctions_;
};

// Throws the Context's GpuError for a requested device index (--device, SIXWAY_DEVICE) that no device has,
// from a bare instance: so a program may reject it before it opens a window.
void checkRequestedDevice(const ContextOptions& options);
// One line per physical device: "index: name (type)", for --device and `sixway info`.
std::vector<std::string> listPhysicalDevices(VkInstance instance);
const char* deviceTypeName(VkPhysicalDeviceType type);
std::string formatBytes(uint64_t bytes);

}  // namespace sixway::gpu
