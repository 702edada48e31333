#pragma once
// The Vulkan functions sixway calls, as pointers. sixway's libraries build with VK_NO_PROTOTYPES, so every
// call goes through these: the linked loader's functions by default, or those an engine's
// vkGetInstanceProcAddr gives for its instance while that engine's device is in use (EngineVulkanFunctions).
#include <vulkan/vulkan.h>

// Taken with vkGetInstanceProcAddr(NULL, name).
#define SIXWAY_VULKAN_GLOBAL_FUNCTIONS(X) \
  X(vkCreateInstance)                     \
  X(vkEnumerateInstanceLayerProperties)

// Taken with vkGetInstanceProcAddr(instance, name): instance and device functions alike, as the loader's
// dispatching entry points, which serve every device of every instance.
#define SIXWAY_VULKAN_FUNCTIONS(X)            \
  X(vkAllocateCommandBuffers)                 \
  X(vkAllocateMemory)                         \
  X(vkBeginCommandBuffer)                     \
  X(vkBindBufferMemory)                       \
  X(vkBindImageMemory)                        \
  X(vkCmdBeginRendering)                      \
  X(vkCmdBindIndexBuffer)                     \
  X(vkCmdBindPipeline)                        \
  X(vkCmdBindVertexBuffers)                   \
  X(vkCmdCopyBuffer)                          \
  X(vkCmdCopyBufferToImage)                   \
  X(vkCmdCopyImageToBuffer)                   \
  X(vkCmdDispatch)                            \
  X(vkCmdDispatchIndirect)                    \
  X(vkCmdDraw)                                \
  X(vkCmdDrawIndexed)                         \
  X(vkCmdEndRendering)                        \
  X(vkCmdExecuteCommands)                     \
  X(vkCmdFillBuffer)                          \
  X(vkCmdPipelineBarrier2)                    \
  X(vkCmdPushConstants)                       \
  X(vkCmdResetQueryPool)                      \
  X(vkCmdSetScissor)                          \
  X(vkCmdSetViewport)                         \
  X(vkCmdUpdateBuffer)                        \
  X(vkCmdWriteTimestamp2)                     \
  X(vkCreateBuffer)                           \
  X(vkCreateBufferView)                       \
  X(vkCreateCommandPool)                      \
  X(vkCreateComputePipelines)                 \
  X(vkCreateDescriptorSetLayout)              \
  X(vkCreateDevice)                           \
  X(vkCreateFence)                            \
  X(vkCreateGraphicsPipelines)                \
  X(vkCreateImage)                            \
  X(vkCreateImageView)                        \
  X(vkCreatePipelineCache)                    \
  X(vkCreatePipelineLayout)                   \
  X(vkCreateQueryPool)                        \
  X(vkCreateSampler)                          \
  X(vkCreateShaderModule)                     \
  X(vkDestroyBuffer)                          \
  X(vkDestroyBufferView)                      \
  X(vkDestroyCommandPool)                     \
  X(vkDestroyDescriptorSetLayout)             \
  X(vkDestroyDevice)                          \
  X(vkDestroyFence)                           \
  X(vkDestroyImage)                           \
  X(vkDestroyImageView)                       \
  X(vkDestroyInstance)                        \
  X(vkDestroyPipeline)                        \
  X(vkDestroyPipelineCache)                   \
  X(vkDestroyPipelineLayout)                  \
  X(vkDestroyQueryPool)                       \
  X(vkDestroySampler)                         \
  X(vkDestroyShaderModule)                    \
  X(vkEndCommandBuffer)                       \
  X(vkEnumerateDeviceExtensionProperties)     \
  X(vkEnumeratePhysicalDevices)               \
  X(vkFreeMemory)                             \
  X(vkGetBufferMemoryRequirements)            \
  X(vkGetDeviceProcAddr)                      \
  X(vkGetDeviceQueue)                         \
  X(vkGetImageMemoryRequirements)             \
  X(vkGetPhysicalDeviceFeatures2)             \
  X(vkGetPhysicalDeviceMemoryProperties)      \
  X(vkGetPhysicalDeviceProperties)            \
  X(vkGetPhysicalDeviceProperties2)           \
  X(vkGetPhysicalDeviceQueueFamilyProperties) \
  X(vkGetPipelineCacheData)                   \
  X(vkGetQueryPoolResults)                    \
  X(vkMapMemory)                              \
  X(vkQueueSubmit)                            \
  X(vkResetCommandBuffer)                     \
  X(vkResetFences)                            \
  X(vkWaitForFences)

namespace sixway::gpu {

#define SIXWAY_DECLARE_VULKAN_FUNCTION(name) extern PFN_##name name;
SIXWAY_VULKAN_GLOBAL_FUNCTIONS(SIXWAY_DECLARE_VULKAN_FUNCTION)
SIXWAY_VULKAN_FUNCTIONS(SIXWAY_DECLARE_VULKAN_FUNCTION)
SIXWAY_DECLARE_VULKAN_FUNCTION(vkGetInstanceProcAddr)
#undef SIXWAY_DECLARE_VULKAN_FUNCTION

// While it lives, the process's Vulkan functions are those `getInstanceProcAddr` gives for `instance` (an
// engine's loader, or a layer of its own in front of it); when the last one goes, the linked loader's again.
// Several may live at once when they share the same getInstanceProcAddr. Made and destroyed while no other
// sixway call runs (with the engine device that holds it). GpuError, the functions left as they were, for a
// function it does not give (naming it) or for a different getInstanceProcAddr while another one lives.
class EngineVulkanFunctions {
 public:
  EngineVulkanFunctions(PFN_vkGetInstanceProcAddr getInstanceProcAddr, VkInstance instance);
  ~EngineVulkanFunctions();
  EngineVulkanFunctions(const EngineVulkanFunctions&) = delete;
  EngineVulkanFunctions& operator=(const EngineVulkanFunctions&) = delete;
};

}  // namespace sixway::gpu
