#include "gpu/feature_merge.h"

#include <algorithm>
#include <cstring>

namespace sixway::gpu {
namespace {

// The first structure of `type` in the chain of `info` (the engine's structures, which it lets us change).
template <typename Features>
Features* find(const VkDeviceCreateInfo& info, VkStructureType type) {
  for (auto* s = static_cast<VkBaseOutStructure*>(const_cast<void*>(info.pNext)); s; s = s->pNext)
    if (s->sType == type) return reinterpret_cast<Features*>(s);
  return nullptr;
}

void append(VkDeviceCreateInfo& info, void* own) {
  auto* added = static_cast<VkBaseOutStructure*>(own);
  added->pNext = nullptr;
  if (!info.pNext) {
    info.pNext = added;
    return;
  }
  auto* last = static_cast<VkBaseOutStructure*>(const_cast<void*>(info.pNext));
  while (last->pNext) last = last->pNext;
  last->pNext = added;
}

// Switches a feature on: in the chain's aggregate of its version when there is one, else in the chain's own
// structure of it, else in ours, appended once.
template <typename Own>
void enable(VkDeviceCreateInfo& info, VkBool32 wanted, VkBool32* aggregate, Own& own, VkBool32 Own::*field) {
  if (!wanted) return;
  if (aggregate) {
    *aggregate = VK_TRUE;
    return;
  }
  Own* theirs = find<Own>(info, own.sType);
  if (!theirs) {
    append(info, &own);
    theirs = &own;
  }
  theirs->*field = VK_TRUE;
}

}  // namespace

FeatureMerge::FeatureMerge(const DeviceFeatures& wanted, bool cooperativeMatrix,
                           const std::vector<const char*>& needed, VkDeviceCreateInfo& info,
                           std::vector<const char*>& extensions) {
  // Core features: the chain's VkPhysicalDeviceFeatures2, else pEnabledFeatures (they may not be both), else
  // ours.
  VkPhysicalDeviceFeatures* core = nullptr;
  if (auto* features2 = find<VkPhysicalDeviceFeatures2>(info, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2))
    core = &features2->features;
  else if (info.pEnabledFeatures)
    core = const_cast<VkPhysicalDeviceFeatures*>(info.pEnabledFeatures);
  else {
    append(info, &features_);
    core = &features_.features;
  }
  const VkPhysicalDeviceFeatures& w = wanted.core();
  core->shaderInt64 |= w.shaderInt64;
  core->fragmentStoresAndAtomics |= w.fragmentStoresAndAtomics;
  core->shaderStorageImageWriteWithoutFormat |= w.shaderStorageImageWriteWithoutFormat;

  auto* v11 =
      find<VkPhysicalDeviceVulkan11Features>(info, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES);
  auto* v12 =
      find<VkPhysicalDeviceVulkan12Features>(info, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES);
  auto* v13 =
      find<VkPhysicalDeviceVulkan13Features>(info, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES);
  enable(info, wanted.vulkan11().storageBuffer16BitAccess, v11 ? &v11->storageBuffer16BitAccess : nullptr,
         storage16_, &VkPhysicalDevice16BitStorageFeatures::storageBuffer16BitAccess);
  enable(info, wanted.vulkan12().shaderFloat16, v12 ? &v12->shaderFloat16 : nullptr, float16_,
         &VkPhysicalDeviceShaderFloat16Int8Features::shaderFloat16);
  enable(info, wanted.vulkan12().hostQueryReset, v12 ? &v12->hostQueryReset : nullptr, queryReset_,
         &VkPhysicalDeviceHostQueryResetFeatures::hostQueryReset);
  enable(info, wanted.vulkan12().vulkanMemoryModel, v12 ? &v12->vulkanMemoryModel : nullptr, memoryModel_,
         &VkPhysicalDeviceVulkanMemoryModelFeatures::vulkanMemoryModel);
  enable(info, wanted.vulkan12().vulkanMemoryModelDeviceScope,
         v12 ? &v12->vulkanMemoryModelDeviceScope : nullptr, memoryModel_,
         &VkPhysicalDeviceVulkanMemoryModelFeatures::vulkanMemoryModelDeviceScope);
  enable(info, wanted.vulkan13().synchronization2, v13 ? &v13->synchronization2 : nullptr, synchronization2_,
         &VkPhysicalDeviceSynchronization2Features::synchronization2);
  enable(info, wanted.vulkan13().dynamicRendering, v13 ? &v13->dynamicRendering : nullptr, dynamicRendering_,
         &VkPhysicalDeviceDynamicRenderingFeatures::dynamicRendering);
  enable(info, wanted.vulkan13().maintenance4, v13 ? &v13->maintenance4 : nullptr, maintenance4_,
         &VkPhysicalDeviceMaintenance4Features::maintenance4);
  enable(info, wanted.vulkan13().subgroupSizeControl, v13 ? &v13->subgroupSizeControl : nullptr,
         subgroupSize_, &VkPhysicalDeviceSubgroupSizeControlFeatures::subgroupSizeControl);
  enable(info, wanted.atomicFloat().shaderBufferFloat32AtomicAdd, nullptr, atomics_,
         &VkPhysicalDeviceShaderAtomicFloatFeaturesEXT::shaderBufferFloat32AtomicAdd);
  enable(info, VkBool32(cooperativeMatrix), nullptr, matrix_,
         &VkPhysicalDeviceCooperativeMatrixFeaturesNV::cooperativeMatrix);

  for (const char* name : needed)
    if (std::none_of(extensions.begin(), extensions.end(),
                     [&](const char* e) { return std::strcmp(e, name) == 0; }))
      extensions.push_back(name);
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
}

}  // namespace sixway::gpu
