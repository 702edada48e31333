#pragma once
// The Vulkan features and extensions sixway's shaders and host use, as one VkPhysicalDeviceFeatures2 chain
// (1.1, 1.2, 1.3 and float atomics): what a device supports, what sixway enables on its own device, and what
// is missing from a device an engine created (docs/embedding.md, "The device").
#include <vulkan/vulkan.h>

#include <string>
#include <vector>

namespace sixway::gpu {

class DeviceFeatures {
 public:
  DeviceFeatures();
  DeviceFeatures(const DeviceFeatures& other);
  DeviceFeatures& operator=(const DeviceFeatures& other);

  // What `device` supports.
  static DeviceFeatures supportedBy(VkPhysicalDevice device);
  // Read from the pNext chain a device was created with (VkPhysicalDeviceFeatures2 or
  // VkDeviceCreateInfo::pNext): the 1.1-1.3 aggregates, or the structures of the promoted features sixway
  // uses (synchronization2, dynamic rendering, maintenance4, ...); structures the chain lacks count as all
  // features off.
  static DeviceFeatures fromChain(const void* chain);
  // What sixway enables: the required features, and the optional ones (16-bit storage, fp16 arithmetic,
  // 64-bit integers, ...) where `supported` has them.
  static DeviceFeatures toEnable(const DeviceFeatures& supported);

  // The required features this set lacks, named as in the Vulkan spec ("synchronization2", ...); empty
  // when none is missing.
  std::vector<std::string> missingRequired() const;

  // The chain, for VkDeviceCreateInfo::pNext or vkGetPhysicalDeviceFeatures2; valid while this lives.
  VkPhysicalDeviceFeatures2* chain() { return &features_; }

  const VkPhysicalDeviceFeatures& core() const { return features_.features; }
  const VkPhysicalDeviceVulkan11Features& vulkan11() const { return v11_; }
  const VkPhysicalDeviceVulkan12Features& vulkan12() const { return v12_; }
  const VkPhysicalDeviceVulkan13Features& vulkan13() const { return v13_; }
  const VkPhysicalDeviceShaderAtomicFloatFeaturesEXT& atomicFloat() const { return atomics_; }

 private:
  void link();
  VkPhysicalDeviceShaderAtomicFloatFeaturesEXT atomics_{};
  VkPhysicalDeviceVulkan11Features v11_{};
  VkPhysicalDeviceVulkan12Features v12_{};
  VkPhysicalDeviceVulkan13Features v13_{};
  VkPhysicalDeviceFeatures2 features_{};
};

// The device extensions sixway needs (push descriptors, float atomics).
std::vector<const char*> requiredDeviceExtensions();

// Whether `device` offers the device extension `name`.
bool hasDeviceExtension(VkPhysicalDevice device, const char* name);

}  // namespace sixway::gpu
