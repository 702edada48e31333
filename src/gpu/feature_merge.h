#pragma once
// sixway's device features merged into an engine's VkDeviceCreateInfo: each feature switched on in the
// structure of the engine's chain that holds it (its VkPhysicalDeviceFeatures2 or pEnabledFeatures, a 1.1-1.3
// aggregate, or the promoted feature's own structure); what no structure holds is added as the promoted
// feature's own structure (never an aggregate, which would clash with structures of its version the engine
// has), so no sType appears twice. docs/embedding.md, "The device".
#include <vulkan/vulkan.h>

#include <vector>

#include "gpu/device_features.h"

namespace sixway::gpu {

class FeatureMerge {
 public:
  // Merges `wanted` (and the NV cooperative matrix when `cooperativeMatrix`) into `info`'s chain, and the
  // extensions into `extensions`, which `info` then names. The structures added live in this object.
  FeatureMerge(const DeviceFeatures& wanted, bool cooperativeMatrix, const std::vector<const char*>& needed,
               VkDeviceCreateInfo& info, std::vector<const char*>& extensions);
  FeatureMerge(const FeatureMerge&) = delete;
  FeatureMerge& operator=(const FeatureMerge&) = delete;

 private:
  VkPhysicalDeviceFeatures2 features_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  VkPhysicalDevice16BitStorageFeatures storage16_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_16BIT_STORAGE_FEATURES};
  VkPhysicalDeviceShaderFloat16Int8Features float16_{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_FLOAT16_INT8_FEATURES};
  VkPhysicalDeviceHostQueryResetFeatures queryReset_{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_HOST_QUERY_RESET_FEATURES};
  VkPhysicalDeviceVulkanMemoryModelFeatures memoryModel_{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_MEMORY_MODEL_FEATURES};
  VkPhysicalDeviceSynchronization2Features synchronization2_{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES};
  VkPhysicalDeviceDynamicRenderingFeatures dynamicRendering_{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES};
  VkPhysicalDeviceMaintenance4Features maintenance4_{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES};
  VkPhysicalDeviceSubgroupSizeControlFeatures subgroupSize_{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_SIZE_CONTROL_FEATURES};
  VkPhysicalDeviceShaderAtomicFloatFeaturesEXT atomics_{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};
  VkPhysicalDeviceCooperativeMatrixFeaturesNV matrix_{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_COOPERATIVE_MATRIX_FEATURES_NV};
};

}  // namespace sixway::gpu
