#pragma once
// Cooperative matrices (VK_NV_cooperative_matrix: the tensor cores of NVIDIA GPUs) as the network's conv2d
// uses them (shaders/nn/conv2d_matrix.comp): fp16 A and B, fp32 accumulators, subgroup scope, subgroups of 32
// invocations, fp16 arithmetic, 16-bit storage buffers and the Vulkan memory model. Where a device offers
// several such shapes, the first it lists (the driver lists its preferred first).
#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

namespace sixway::gpu {

struct MatrixShape {
  uint32_t m = 0, n = 0, k = 0;  // A is m x k, B k x n; all 0: none
  explicit operator bool() const { return m != 0; }
};

// What the device has enabled (or will enable) beside the extension.
struct MatrixPrerequisites {
  uint32_t subgroupSize = 0;
  bool shaderFloat16 = false, storage16Bit = false, vulkanMemoryModel = false;
};

// Whether `device` has VK_NV_cooperative_matrix with its cooperativeMatrix feature.
bool hasCooperativeMatrix(VkPhysicalDevice device);

// The shape `device` offers, or none when it lacks the extension, the feature, a shape the kernel can use or
// one of the prerequisites.
MatrixShape offeredMatrixShape(VkInstance instance, VkPhysicalDevice device, const MatrixPrerequisites& has);

// Whether a device created with `extensions` and the feature chain `chain` (VkDeviceCreateInfo::pNext) has
// cooperative matrices enabled.
bool chainEnablesCooperativeMatrix(const std::vector<std::string>& extensions, const void* chain);

}  // namespace sixway::gpu
