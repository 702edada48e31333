#pragma once
// Draw commands recorded straight into a command buffer: what gpu::Sequence records into its own, and what
// sixway records into an engine's inside the engine's rendering (no barriers, no timestamps: neither is
// allowed there).
#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "gpu/sequence.h"

namespace sixway::gpu {

class Buffer;
class Context;
class Pipeline;

// Pushes `bindings` (one per binding of the pipeline's set 0, VK_KHR_push_descriptor) for the pipeline's
// bind point. Throws GpuError for bindings that do not match the pipeline's.
void pushBindings(const Context& context, VkCommandBuffer commands, const Pipeline& pipeline,
                  const std::vector<Binding>& bindings);
// One draw inside a rendering whose attachments are `targets` in size: viewport and scissor (Draw::area),
// pipeline, bindings, push constants, vertex and index buffers, the draw. Throws GpuError for a compute
// pipeline or push constants of the wrong size.
void recordDraw(const Context& context, VkCommandBuffer commands, const Draw& draw, VkExtent2D targets);
// `bytes` of `values` into `buffer` from its start (vkCmdUpdateBuffer, in pieces of its 64 KiB limit).
void recordBufferUpdate(VkCommandBuffer commands, VkBuffer buffer, const std::byte* values, uint64_t bytes);
// recordBufferUpdate of each frame-parameter buffer's host copy (MemoryKind::FrameParameters), outside a
// render pass; the caller places the barrier before their readers.
void recordParameterUpdates(VkCommandBuffer commands, std::span<const Buffer* const> buffers);

}  // namespace sixway::gpu
