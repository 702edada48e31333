// DeviceFeatures::fromChain reads what an engine enabled in either form: the 1.1-1.3 aggregates or the
// structures of the promoted features, and names what is missing either way.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "gpu/device_features.h"

namespace sixway::gpu {
namespace {

// An engine's chain with sixway's required features in their own structures, no 1.3 aggregate.
struct SeparateStructs {
  VkPhysicalDeviceShaderAtomicFloatFeaturesEXT atomics{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};
  VkPhysicalDeviceMaintenance4Features maintenance4{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES,
                                                    &atomics};
  VkPhysicalDeviceDynamicRenderingFeatures dynamicRendering{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES, &maintenance4};
  VkPhysicalDeviceSynchronization2Features synchronization2{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES, &dynamicRendering};
  VkPhysicalDevice16BitStorageFeatures storage16{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_16BIT_STORAGE_FEATURES,
                                                 &synchronization2};
  VkPhysicalDeviceShaderFloat16Int8Features float16{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_FLOAT16_INT8_FEATURES, &storage16};
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &float16};

  SeparateStructs() {
    atomics.shaderBufferFloat32AtomicAdd = VK_TRUE;
    maintenance4.maintenance4 = VK_TRUE;
    dynamicRendering.dynamicRendering = VK_TRUE;
    synchronization2.synchronization2 = VK_TRUE;
    storage16.storageBuffer16BitAccess = VK_TRUE;
    float16.shaderFloat16 = VK_TRUE;
    features.features.shaderInt64 = VK_TRUE;
  }
};

TEST(DeviceFeatures, TheFeaturesInTheirOwnStructuresCountAsTheAggregatesWould) {
  SeparateStructs chain;
  const DeviceFeatures found = DeviceFeatures::fromChain(&chain.features);
  EXPECT_TRUE(found.missingRequired().empty());
  EXPECT_TRUE(found.vulkan13().synchronization2);
  EXPECT_TRUE(found.vulkan13().dynamicRendering);
  EXPECT_TRUE(found.vulkan13().maintenance4);
  EXPECT_TRUE(found.vulkan11().storageBuffer16BitAccess);
  EXPECT_TRUE(found.vulkan12().shaderFloat16);
  EXPECT_TRUE(found.core().shaderInt64);
  EXPECT_FALSE(found.vulkan12().vulkanMemoryModel) << "a structure the chain lacks is all off";
}

TEST(DeviceFeatures, AFeatureOffInItsOwnStructureIsNamed) {
  SeparateStructs chain;
  chain.maintenance4.maintenance4 = VK_FALSE;
  EXPECT_EQ(DeviceFeatures::fromChain(&chain.features).missingRequired(),
            std::vector<std::string>{"maintenance4"});
  chain.dynamicRendering.pNext = chain.maintenance4.pNext;  // the maintenance4 structure left out
  chain.maintenance4.maintenance4 = VK_TRUE;
  EXPECT_EQ(DeviceFeatures::fromChain(&chain.features).missingRequired(),
            std::vector<std::string>{"maintenance4"});
}

TEST(DeviceFeatures, TheAggregatesAreReadAsBefore) {
  SeparateStructs separate;  // only its atomics: the aggregates carry the rest
  VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
                                       &separate.atomics};
  v13.synchronization2 = v13.dynamicRendering = v13.maintenance4 = VK_TRUE;
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &v13};
  EXPECT_TRUE(DeviceFeatures::fromChain(&features).missingRequired().empty());
  v13.dynamicRendering = VK_FALSE;
  EXPECT_EQ(DeviceFeatures::fromChain(&features).missingRequired(),
            std::vector<std::string>{"dynamicRendering"});
}

}  // namespace
}  // namespace sixway::gpu
