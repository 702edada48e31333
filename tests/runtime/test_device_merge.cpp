// DeviceRequirements::mergeInto: sixway's features merged into an engine's VkDeviceCreateInfo in whichever
// form the engine wrote its own (aggregates, the promoted features' structures, pEnabledFeatures), with no
// sType twice; a device made from the merged info runs sixway under validation.
#include <gtest/gtest.h>
#include <sixway/device.h>
#include <sixway/smoke_simulation.h>

#include <set>
#include <vector>

#include "gpu/check.h"
#include "gpu/device_features.h"
#include "runtime/engine_harness.h"
#include "support/temp_dir.h"

namespace sixway::test {
namespace {

// The sTypes of the chain, each once (a repeated one fails the test).
std::set<VkStructureType> chainTypes(const VkDeviceCreateInfo& info) {
  std::set<VkStructureType> types;
  for (auto* s = static_cast<const VkBaseInStructure*>(info.pNext); s; s = s->pNext)
    EXPECT_TRUE(types.insert(s->sType).second) << "sType " << s->sType << " twice";
  return types;
}

TEST(DeviceMerge, IntoTheEnginesOwnStructuresWithoutAnAggregate) {
  Device own;
  DeviceRequirements needs(runtime::Access::context(own).physicalDevice());
  VkPhysicalDeviceDynamicRenderingFeatures dynamicRendering{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES};
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &dynamicRendering};
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
  std::vector<const char*> extensions{VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
  needs.mergeInto(info, extensions);
  const std::set<VkStructureType> types = chainTypes(info);
  EXPECT_TRUE(dynamicRendering.dynamicRendering) << "not switched on in the engine's own structure";
  EXPECT_FALSE(types.count(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES))
      << "an aggregate beside it";
  EXPECT_TRUE(gpu::DeviceFeatures::fromChain(info.pNext).missingRequired().empty());
  EXPECT_EQ(info.enabledExtensionCount, uint32_t(extensions.size()));
  EXPECT_EQ(std::set<std::string>(extensions.begin(), extensions.end()).size(), extensions.size())
      << "an extension twice";
}

TEST(DeviceMerge, IntoTheAggregatesAndBesideACoreFeatureStruct) {
  Device own;
  const VkPhysicalDevice physicalDevice = runtime::Access::context(own).physicalDevice();
  DeviceRequirements needs(physicalDevice);
  VkPhysicalDeviceVulkan11Features v11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &v11};
  VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES, &v12};
  VkPhysicalDeviceFeatures core{};
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &v13};
  info.pEnabledFeatures = &core;
  std::vector<const char*> extensions;
  needs.mergeInto(info, extensions);
  const std::set<VkStructureType> types = chainTypes(info);
  EXPECT_TRUE(v13.synchronization2 && v13.dynamicRendering && v13.maintenance4);
  EXPECT_FALSE(types.count(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2)) << "beside pEnabledFeatures";
  EXPECT_FALSE(types.count(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES))
      << "beside the aggregate";
  EXPECT_TRUE(types.count(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT));
  EXPECT_TRUE(gpu::DeviceFeatures::fromChain(info.pNext).missingRequired().empty());
  EXPECT_THROW(needs.mergeInto(info, extensions), std::invalid_argument) << "one merge per object";
}

// The engine's device made from its own info with sixway's merged in: sixway takes it and simulates.
TEST(DeviceMerge, ADeviceFromTheMergedInfoRunsSixway) {
  TempDir dir;
  Device own({.validate = true});
  const gpu::Context& context = runtime::Access::context(own);
  DeviceRequirements needs(context.physicalDevice());
  VkPhysicalDeviceDynamicRenderingFeatures dynamicRendering{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES};
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &dynamicRendering};
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = context.queueFamily();
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queueInfo;
  std::vector<const char*> extensions;
  needs.mergeInto(info, extensions);
  VkDevice device = VK_NULL_HANDLE;
  SIXWAY_VK(vkCreateDevice(context.physicalDevice(), &info, nullptr, &device));
  VkQueue queue = VK_NULL_HANDLE;
  vkGetDeviceQueue(device, context.queueFamily(), 0, &queue);
  {
    Device engineDevice(EngineDevice{context.instance(),
                                     context.physicalDevice(),
                                     device,
                                     queue,
                                     context.queueFamily(),
                                     {extensions.begin(), extensions.end()},
                                     info.pNext,
                                     2});
    SmokeSimulation simulation(engineDevice, sceneWithoutObstacles(dir.path()));
    simulation.advance();
    EXPECT_EQ(simulation.framesSimulated(), 1);
  }
  vkDestroyDevice(device, nullptr);
  EXPECT_EQ(own.validationMessages(), 0u);
}

}  // namespace
}  // namespace sixway::test
