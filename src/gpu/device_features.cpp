#include "gpu/device_features.h"
#include "gpu/vulkan_functions.h"

#include <algorithm>
#include <cstring>

namespace sixway::gpu {

DeviceFeatures::DeviceFeatures() {
  atomics_.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT;
  v11_.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES;
  v12_.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
  v13_.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
  features_.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  link();
}

DeviceFeatures::DeviceFeatures(const DeviceFeatures& other) {
  *this = other;
}

DeviceFeatures& DeviceFeatures::operator=(const DeviceFeatures& other) {
  atomics_ = other.atomics_;
  v11_ = other.v11_;
  v12_ = other.v12_;
  v13_ = other.v13_;
  features_ = other.features_;
  link();
  return *this;
}

void DeviceFeatures::link() {
  features_.pNext = &v13_;
  v13_.pNext = &v12_;
  v12_.pNext = &v11_;
  v11_.pNext = &atomics_;
  atomics_.pNext = nullptr;
}

DeviceFeatures DeviceFeatures::supportedBy(VkPhysicalDevice device) {
  DeviceFeatures supported;
  vkGetPhysicalDeviceFeatures2(device, supported.chain());
  return supported;
}

namespace {

// A chain element as the structure its sType names.
template <typename Features>
const Features& as(const VkBaseInStructure* s) {
  return *reinterpret_cast<const Features*>(s);
}

}  // namespace

DeviceFeatures DeviceFeatures::fromChain(const void* chain) {
  DeviceFeatures found;
  // Copy each known structure's features, keeping our own sType/pNext links.
  auto copyFeatures = [](auto& into, const VkBaseInStructure* from) {
    void* next = into.pNext;
    into = *reinterpret_cast<const std::remove_reference_t<decltype(into)>*>(from);
    into.pNext = next;
  };
  for (auto* s = static_cast<const VkBaseInStructure*>(chain); s; s = s->pNext) {
    switch (s->sType) {
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2:
        copyFeatures(found.features_, s);
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES:
        copyFeatures(found.v11_, s);
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES:
        copyFeatures(found.v12_, s);
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES:
        copyFeatures(found.v13_, s);
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT:
        copyFeatures(found.atomics_, s);
        break;
      default:
        break;
    }
  }
  // The same features enabled through their own structures (the extensions promoted into 1.1-1.3), which a
  // chain holds instead of the aggregate of their version.
  for (auto* s = static_cast<const VkBaseInStructure*>(chain); s; s = s->pNext) {
    switch (s->sType) {
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES:
        found.v13_.synchronization2 |= as<VkPhysicalDeviceSynchronization2Features>(s).synchronization2;
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES:
        found.v13_.dynamicRendering |= as<VkPhysicalDeviceDynamicRenderingFeatures>(s).dynamicRendering;
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES:
        found.v13_.maintenance4 |= as<VkPhysicalDeviceMaintenance4Features>(s).maintenance4;
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_SIZE_CONTROL_FEATURES:
        found.v13_.subgroupSizeControl |=
            as<VkPhysicalDeviceSubgroupSizeControlFeatures>(s).subgroupSizeControl;
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_16BIT_STORAGE_FEATURES:
        found.v11_.storageBuffer16BitAccess |=
            as<VkPhysicalDevice16BitStorageFeatures>(s).storageBuffer16BitAccess;
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_FLOAT16_INT8_FEATURES:
        found.v12_.shaderFloat16 |= as<VkPhysicalDeviceShaderFloat16Int8Features>(s).shaderFloat16;
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_HOST_QUERY_RESET_FEATURES:
        found.v12_.hostQueryReset |= as<VkPhysicalDeviceHostQueryResetFeatures>(s).hostQueryReset;
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_MEMORY_MODEL_FEATURES: {
        const auto& model = as<VkPhysicalDeviceVulkanMemoryModelFeatures>(s);
        found.v12_.vulkanMemoryModel |= model.vulkanMemoryModel;
        found.v12_.vulkanMemoryModelDeviceScope |= model.vulkanMemoryModelDeviceScope;
        break;
      }
      default:
        break;
    }
  }
  found.link();
  return found;
}

DeviceFeatures DeviceFeatures::toEnable(const DeviceFeatures& supported) {
  DeviceFeatures enable;
  // Float atomic add: the simulation sums obstacle forces with it.
  enable.atomics_.shaderBufferFloat32AtomicAdd = VK_TRUE;
  enable.v11_.storageBuffer16BitAccess = supported.v11_.storageBuffer16BitAccess;
  enable.v12_.shaderFloat16 = supported.v12_.shaderFloat16;
  enable.v12_.hostQueryReset = supported.v12_.hostQueryReset;
  // The Vulkan memory model: cooperative-matrix shaders declare it (SPV_NV_cooperative_matrix requires it).
  // Enabled only with its device scope: with the model on and the scope off, the atomics of every other
  // shader (GLSL's default, Device scope) are invalid (VUID-RuntimeSpirv-vulkanMemoryModel-06265).
  const bool memoryModel = supported.v12_.vulkanMemoryModel && supported.v12_.vulkanMemoryModelDeviceScope;
  enable.v12_.vulkanMemoryModel = memoryModel;
  enable.v12_.vulkanMemoryModelDeviceScope = memoryModel;
  enable.v13_.synchronization2 = VK_TRUE;
  enable.v13_.dynamicRendering = VK_TRUE;
  enable.v13_.subgroupSizeControl = supported.v13_.subgroupSizeControl;
  enable.v13_.maintenance4 = VK_TRUE;  // workgroup sizes as specialization constants (LocalSizeId)
  enable.features_.features.shaderInt64 = supported.features_.features.shaderInt64;
  // An engine's rendering with several colour attachments: the smoke blends into one, the others are masked.
  enable.features_.features.independentBlend = supported.features_.features.independentBlend;
  enable.features_.features.fragmentStoresAndAtomics = supported.features_.features.fragmentStoresAndAtomics;
  enable.features_.features.shaderStorageImageWriteWithoutFormat =
      supported.features_.features.shaderStorageImageWriteWithoutFormat;
  return enable;
}

std::vector<std::string> DeviceFeatures::missingRequired() const {
  std::vector<std::string> missing;
  if (!v13_.synchronization2) missing.push_back("synchronization2");
  if (!v13_.dynamicRendering) missing.push_back("dynamicRendering");
  if (!v13_.maintenance4) missing.push_back("maintenance4");
  if (!atomics_.shaderBufferFloat32AtomicAdd) missing.push_back("shaderBufferFloat32AtomicAdd");
  return missing;
}

bool hasDeviceExtension(VkPhysicalDevice device, const char* name) {
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
  return std::any_of(extensions.begin(), extensions.end(),
                     [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

std::vector<const char*> requiredDeviceExtensions() {
  return {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME, VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME};
}

}  // namespace sixway::gpu
