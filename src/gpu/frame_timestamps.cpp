#include "gpu/frame_timestamps.h"

#include <algorithm>

#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/vulkan_functions.h"

namespace sixway::gpu {

FrameTimestamps::FrameTimestamps(const Context& context)
    : context_(&context), slots_(std::min<uint32_t>(context.framesInFlight(), 8)) {
  if (!context.capabilities().timestamps) return;
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = 2 * slots_;
  SIXWAY_VK(vkCreateQueryPool(context.device(), &info, context.allocator(), &queries_));
}

FrameTimestamps::~FrameTimestamps() {
  if (queries_) vkDestroyQueryPool(context_->device(), queries_, context_->allocator());
}

void FrameTimestamps::recordReset(VkCommandBuffer commands, uint64_t frame) {
  if (!queries_) return;
  slot_ = uint32_t(frame % slots_);
  if (pending_[slot_]) {  // that frame has completed: its results are there (not if it wrote none)
    uint64_t ticks[2];
    if (vkGetQueryPoolResults(context_->device(), queries_, 2 * slot_, 2, sizeof(ticks), ticks,
                              sizeof(uint64_t), VK_QUERY_RESULT_64_BIT) == VK_SUCCESS) {
      const uint32_t bits = context_->capabilities().timestampValidBits;
      const uint64_t mask = bits >= 64 ? ~0ull : (1ull << bits) - 1;
      milliseconds_ = double(((ticks[1] & mask) - (ticks[0] & mask)) & mask) *
                      context_->capabilities().timestampPeriodNs * 1e-6;
    }
  }
  vkCmdResetQueryPool(commands, queries_, 2 * slot_, 2);
  pending_[slot_] = frame;
  begun_ = ended_ = false;
}

void FrameTimestamps::recordBegin(VkCommandBuffer commands) {
  if (!queries_ || begun_) return;
  vkCmdWriteTimestamp2(commands, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries_, 2 * slot_);
  begun_ = true;
}

void FrameTimestamps::recordEnd(VkCommandBuffer commands) {
  if (!queries_ || !begun_ || ended_) return;
  vkCmdWriteTimestamp2(commands, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries_, 2 * slot_ + 1);
  ended_ = true;
}

}  // namespace sixway::gpu
