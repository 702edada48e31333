#pragma once
// Record, submit and wait for a short command buffer (uploads, readbacks, layout set-up).
// Not for per-frame work: frames are recorded once into a Sequence and replayed.
#include <vulkan/vulkan.h>

#include <functional>

namespace sixway::gpu {

class Context;

void submitOnce(const Context& context, const std::function<void(VkCommandBuffer)>& record);

// Orders every earlier write on the queue before every later access (a global memory barrier).
void recordFullBarrier(VkCommandBuffer commands);

}  // namespace sixway::gpu
