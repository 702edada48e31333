#pragma once
// GPU time of work recorded straight into a caller's command buffer where a gpu::Sequence's stages cannot
// go (inside the engine's render pass): two timestamps per frame in flight, their queries reset outside the
// pass, written around the work, and read without waiting once the frame has completed (framesInFlight frames
// later, by the engine's contract).
#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>

namespace sixway::gpu {

class Context;

class FrameTimestamps {
 public:
  explicit FrameTimestamps(const Context& context);
  ~FrameTimestamps();
  FrameTimestamps(const FrameTimestamps&) = delete;
  FrameTimestamps& operator=(const FrameTimestamps&) = delete;

  // Outside a render pass, as frame `frame`: reads the times the slot's last frame measured, then resets it.
  void recordReset(VkCommandBuffer commands, uint64_t frame);
  // Around the work, inside or outside a render pass, after recordReset of the same frame; only the first
  // pair of the frame is measured (a query is written once between resets).
  void recordBegin(VkCommandBuffer commands);
  void recordEnd(VkCommandBuffer commands);
  // The work's time in the latest completed frame that measured it; none before (or without timestamps).
  std::optional<double> milliseconds() const { return milliseconds_; }

 private:
  const Context* context_;
  VkQueryPool queries_ = VK_NULL_HANDLE;  // two per frame in flight
  uint32_t slots_ = 0, slot_ = 0;
  bool begun_ = false, ended_ = false;  // this frame's queries written
  std::optional<uint64_t> pending_[8];  // per slot: the frame whose times it holds, unread
  std::optional<double> milliseconds_;
};

}  // namespace sixway::gpu
