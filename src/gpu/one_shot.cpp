#include "gpu/one_shot.h"

#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/vulkan_functions.h"

namespace sixway::gpu {

void submitOnce(const Context& context, const std::function<void(VkCommandBuffer)>& record) {
  if (context.externalSubmit()) {
    context.externalSubmit()(record);
    return;
  }
  VkDevice device = context.device();
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  poolInfo.queueFamilyIndex = context.queueFamily();
  VkCommandPool pool;
  SIXWAY_VK(vkCreateCommandPool(device, &poolInfo, context.allocator(), &pool));
  VkFence fence = VK_NULL_HANDLE;
  try {
    VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocInfo.commandPool = pool;
    allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocInfo.commandBufferCount = 1;
    VkCommandBuffer cmd;
    SIXWAY_VK(vkAllocateCommandBuffers(device, &allocInfo, &cmd));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    SIXWAY_VK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    SIXWAY_VK(vkEndCommandBuffer(cmd));

    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    SIXWAY_VK(vkCreateFence(device, &fenceInfo, context.allocator(), &fence));
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    SIXWAY_VK(vkQueueSubmit(context.queue(), 1, &submit, fence));
    context.countHostWait();
    SIXWAY_VK(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX));
  } catch (...) {
    if (fence) vkDestroyFence(device, fence, context.allocator());
    vkDestroyCommandPool(device, pool, context.allocator());
    throw;
  }
  vkDestroyFence(device, fence, context.allocator());
  vkDestroyCommandPool(device, pool, context.allocator());
}

void recordFullBarrier(VkCommandBuffer commands) {
  VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  barrier.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  barrier.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  barrier.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  barrier.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.memoryBarrierCount = 1;
  dependency.pMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(commands, &dependency);
}

}  // namespace sixway::gpu
