#include "gpu/cooperative_matrix.h"

#include <algorithm>

#include "gpu/device_features.h"
#include "gpu/vulkan_functions.h"

namespace sixway::gpu {
namespace {

// The kernel's alignment: its matrix loads and stores need offsets and strides of whole 16-byte units, which
// k and n in multiples of 8 give (fp16 rows of k or n, fp32 rows of n); m is a row count, free.
bool usable(const VkCooperativeMatrixPropertiesNV& p) {
  return p.AType == VK_COMPONENT_TYPE_FLOAT16_NV && p.BType == VK_COMPONENT_TYPE_FLOAT16_NV &&
         p.CType == VK_COMPONENT_TYPE_FLOAT32_NV && p.DType == VK_COMPONENT_TYPE_FLOAT32_NV &&
         p.scope == VK_SCOPE_SUBGROUP_NV && p.MSize > 0 && p.MSize <= 32 && p.NSize % 8 == 0 &&
         p.KSize % 8 == 0 && p.NSize > 0 && p.KSize > 0;
}

}  // namespace

bool hasCooperativeMatrix(VkPhysicalDevice device) {
  if (!hasDeviceExtension(device, VK_NV_COOPERATIVE_MATRIX_EXTENSION_NAME)) return false;
  VkPhysicalDeviceCooperativeMatrixFeaturesNV features{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_COOPERATIVE_MATRIX_FEATURES_NV};
  VkPhysicalDeviceFeatures2 features2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features};
  vkGetPhysicalDeviceFeatures2(device, &features2);
  return features.cooperativeMatrix;
}

MatrixShape offeredMatrixShape(VkInstance instance, VkPhysicalDevice device, const MatrixPrerequisites& has) {
  if (has.subgroupSize != 32 || !has.shaderFloat16 || !has.storage16Bit || !has.vulkanMemoryModel ||
      !hasCooperativeMatrix(device))
    return {};
  auto properties = reinterpret_cast<PFN_vkGetPhysicalDeviceCooperativeMatrixPropertiesNV>(
      vkGetInstanceProcAddr(instance, "vkGetPhysicalDeviceCooperativeMatrixPropertiesNV"));
  if (!properties) return {};
  uint32_t count = 0;
  properties(device, &count, nullptr);
  std::vector<VkCooperativeMatrixPropertiesNV> shapes(count,
                                                      {VK_STRUCTURE_TYPE_COOPERATIVE_MATRIX_PROPERTIES_NV});
  properties(device, &count, shapes.data());
  for (const VkCooperativeMatrixPropertiesNV& p : shapes)
    if (usable(p)) return {p.MSize, p.NSize, p.KSize};
  return {};
}

bool chainEnablesCooperativeMatrix(const std::vector<std::string>& extensions, const void* chain) {
  if (std::find(extensions.begin(), extensions.end(), VK_NV_COOPERATIVE_MATRIX_EXTENSION_NAME) ==
      extensions.end())
    return false;
  for (auto* s = static_cast<const VkBaseInStructure*>(chain); s; s = s->pNext)
    if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_COOPERATIVE_MATRIX_FEATURES_NV)
      return reinterpret_cast<const VkPhysicalDeviceCooperativeMatrixFeaturesNV*>(s)->cooperativeMatrix;
  return false;
}

}  // namespace sixway::gpu
