#include "gpu/sequence.h"

#include <algorithm>

#include "gpu/buffer.h"
#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/draw_commands.h"
#include "gpu/image.h"
#include "gpu/one_shot.h"
#include "gpu/pipeline.h"
#include "gpu/vulkan_functions.h"

namespace sixway::gpu {
namespace {

template <typename Handle>
uint64_t key(Handle handle) {
  return reinterpret_cast<uint64_t>(handle);
}

bool readsMemory(Access a) {
  return a != Access::Write;
}
bool writesMemory(Access a) {
  return a != Access::Read;
}

VkRenderingAttachmentInfo attachment(const Image& image, bool clear, VkClearValue value) {
  VkRenderingAttachmentInfo info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  info.imageView = image.view();
  info.imageLayout = VK_IMAGE_LAYOUT_GENERAL;
  info.loadOp = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
  info.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  info.clearValue = value;
  return info;
}

}  // namespace

Sequence::Sequence(const Context& context, uint32_t maxStages) : context_(&context), maxStages_(maxStages) {
  VkDevice device = context.device();
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;  // submit() re-records primary_
  poolInfo.queueFamilyIndex = context.queueFamily();
  SIXWAY_VK(vkCreateCommandPool(device, &poolInfo, context.allocator(), &pool_));
  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = pool_;
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  SIXWAY_VK(vkAllocateCommandBuffers(device, &allocInfo, &primary_));
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  SIXWAY_VK(vkCreateFence(device, &fenceInfo, context.allocator(), &fence_));

  // One copy of the work per frame in flight, each with its own timestamps: frame n runs slot n mod K, whose
  // last run (frame n − K) has completed, so no command buffer or query is in use twice at once.
  slots_.resize(context.framesInFlight());
  resolveEachTimestamp_ = context.driver().driverID == VK_DRIVER_ID_MESA_LLVMPIPE;
  VkCommandBufferInheritanceInfo inheritance{VK_STRUCTURE_TYPE_COMMAND_BUFFER_INHERITANCE_INFO};
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.pInheritanceInfo = &inheritance;
  for (Slot& slot : slots_) {
    allocInfo.level = VK_COMMAND_BUFFER_LEVEL_SECONDARY;
    SIXWAY_VK(vkAllocateCommandBuffers(device, &allocInfo, &slot.commands));
    SIXWAY_VK(vkBeginCommandBuffer(slot.commands, &begin));
    if (!context.capabilities().timestamps) continue;
    VkQueryPoolCreateInfo queryInfo{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    queryInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
    queryInfo.queryCount = 2 * maxStages_ + 1;  // the last: writeTimestamp()'s scratch
    SIXWAY_VK(vkCreateQueryPool(device, &queryInfo, context.allocator(), &slot.queries));
    vkCmdResetQueryPool(slot.commands, slot.queries, 0, 2 * maxStages_ + 1);
  }
}

Sequence::~Sequence() {
  VkDevice device = context_->device();
  for (const Slot& slot : slots_)
    if (slot.queries) vkDestroyQueryPool(device, slot.queries, context_->allocator());
  vkDestroyFence(device, fence_, context_->allocator());
  vkDestroyCommandPool(device, pool_, context_->allocator());
}

void Sequence::requireRecording(const char* what) const {
  if (finished_) throw GpuError(std::string(what) + " after the sequence was finished");
}

void Sequence::beginStage(std::string name) {
  requireRecording("beginStage");
  if (stageOpen_) throw GpuError("stage '" + name + "' begins inside stage '" + stageNames_.back() + "'");
  if (stageNames_.size() == maxStages_)
    throw GpuError("more than " + std::to_string(maxStages_) + " timed stages");
  writeTimestamp(2 * static_cast<uint32_t>(stageNames_.size()));
  stageNames_.push_back(std::move(name));
  stageOpen_ = true;
}

void Sequence::endStage() {
  if (!stageOpen_) throw GpuError("endStage without beginStage");
  writeTimestamp(2 * static_cast<uint32_t>(stageNames_.size()) - 1);
  stageOpen_ = false;
}

void Sequence::writeTimestamp(uint32_t query) {
  for (const Slot& slot : slots_) {
    if (!slot.queries) return;
    vkCmdWriteTimestamp2(slot.commands, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, slot.queries, query);
    if (!resolveEachTimestamp_) continue;
    // Lavapipe (Mesa 22.3) bins a timestamp into llvmpipe's current scene, which takes the time only when the
    // scene is next flushed, and a timestamp write flushes the scene *before* binning its own query. Compute
    // dispatches run at once, so a stage's opening timestamp was taken after the stage's work: a path-trace
    // dispatch of 4.8 s measured 17 ms. A second timestamp right after flushes the first one's scene now. The
    // scratch query is reset before each use (a query is written once between resets).
    const uint32_t scratch = 2 * maxStages_;
    vkCmdResetQueryPool(slot.commands, slot.queries, scratch, 1);
    vkCmdWriteTimestamp2(slot.commands, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, slot.queries, scratch);
  }
}

void Sequence::noteFrameParameters(const Binding& binding) {
  const auto* b = std::get_if<BufferBinding>(&binding);
  if (!b || b->buffer->kind() != MemoryKind::FrameParameters) return;
  const VkBuffer handle = b->buffer->handle();
  if (std::none_of(frameParameters_.begin(), frameParameters_.end(),
                   [&](const FrameParameters& f) { return f.buffer == handle; }))
    frameParameters_.push_back(
        {handle, static_cast<const std::byte*>(b->buffer->mapped()), b->buffer->size()});
}

void Sequence::addTouch(Touch& touch, const Binding& binding) const {
  auto [handle, access] = std::visit(
      [](auto& b) -> std::pair<uint64_t, Access> {
        using B = std::decay_t<decltype(b)>;
        if constexpr (std::is_same_v<B, BufferBinding>)
          return {key(b.buffer->handle()), b.access};
        else if constexpr (std::is_same_v<B, TexelBufferBinding>)
          return {key(b.view->bufferHandle()), b.access};
        else
          return {key(b.image->handle()), b.access};
      },
      binding);
  if (readsMemory(access)) touch.reads.push_back(handle);
  if (writesMemory(access)) touch.writes.push_back(handle);
}

void Sequence::barrierIfHazard(const Touch& touch) {
  auto in = [](const std::set<uint64_t>& set, uint64_t k) { return set.count(k) > 0; };
  bool hazard = std::any_of(touch.reads.begin(), touch.reads.end(),
                            [&](uint64_t k) { return in(writtenSinceBarrier_, k); }) ||
                std::any_of(touch.writes.begin(), touch.writes.end(), [&](uint64_t k) {
                  return in(writtenSinceBarrier_, k) || in(readSinceBarrier_, k);
                });
  if (hazard) {
    // One global memory barrier orders all earlier writes before all later accesses: between
    // dependent passes the GPU drains anyway, and it keeps the bookkeeping to two sets.
    for (const Slot& slot : slots_) recordFullBarrier(slot.commands);
    ++barriers_;
    writtenSinceBarrier_.clear();
    readSinceBarrier_.clear();
  }
  readSinceBarrier_.insert(touch.reads.begin(), touch.reads.end());
  writtenSinceBarrier_.insert(touch.writes.begin(), touch.writes.end());
}

// What every compute dispatch checks and records before its vkCmdDispatch*: the push constants' size, the
// barrier its bindings need, then per slot the pipeline, bindings and push constants.
void Sequence::beginDispatch(const Pipeline& pipeline, const std::vector<Binding>& bindings,
                             std::span<const std::byte> pushConstants) {
  if (pipeline.bindPoint() != VK_PIPELINE_BIND_POINT_COMPUTE)
    throw GpuError(pipeline.name() + ": dispatch needs a compute pipeline");
  if (pushConstants.size() != pipeline.pushConstantBytes())
    throw GpuError(pipeline.name() + ": " + std::to_string(pushConstants.size()) +
                   " bytes of push constants given, the pipeline takes " +
                   std::to_string(pipeline.pushConstantBytes()));
  Touch touch;
  for (const Binding& b : bindings) {
    addTouch(touch, b);
    noteFrameParameters(b);
  }
  barrierIfHazard(touch);
  for (const Slot& slot : slots_) {
    vkCmdBindPipeline(slot.commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
    pushBindings(*context_, slot.commands, pipeline, bindings);
    if (!pushConstants.empty())
      vkCmdPushConstants(slot.commands, pipeline.layout(), pipeline.stages(), 0,
                         static_cast<uint32_t>(pushConstants.size()), pushConstants.data());
  }
}

void Sequence::dispatch(const Pipeline& pipeline, const std::vector<Binding>& bindings,
                        std::span<const std::byte> pushConstants, uint32_t groupsX, uint32_t groupsY,
                        uint32_t groupsZ) {
  requireRecording("dispatch");
  const auto& maxGroups = context_->limits().maxComputeWorkGroupCount;
  if (groupsX > maxGroups[0] || groupsY > maxGroups[1] || groupsZ > maxGroups[2])
    throw GpuError(pipeline.name() + ": dispatch of " + std::to_string(groupsX) + "x" +
                   std::to_string(groupsY) + "x" + std::to_string(groupsZ) +
                   " groups exceeds the device's limit; reduce the grid");
  beginDispatch(pipeline, bindings, pushConstants);
  if (groupsX && groupsY && groupsZ)
    for (const Slot& slot : slots_) vkCmdDispatch(slot.commands, groupsX, groupsY, groupsZ);
}

VkDispatchIndirectCommand linearGroups(const Context& context, uint64_t invocations, uint32_t groupSize,
                                       const std::string& what) {
  const uint64_t groups = (invocations + groupSize - 1) / groupSize;
  const uint64_t maxX = context.limits().maxComputeWorkGroupCount[0];
  const uint64_t x = std::min(groups, maxX), y = (groups + x - 1) / std::max<uint64_t>(x, 1);
  if (y > context.limits().maxComputeWorkGroupCount[1])
    throw GpuError(what + ": " + std::to_string(invocations) +
                   " invocations exceed the device's dispatch limit; reduce the grid");
  return {uint32_t(std::max<uint64_t>(x, 1)), uint32_t(std::max<uint64_t>(y, 1)), 1};
}

void Sequence::dispatchLinear(const Pipeline& pipeline, const std::vector<Binding>& bindings,
                              std::span<const std::byte> pushConstants, uint64_t invocations,
                              uint32_t groupSize) {
  const VkDispatchIndirectCommand groups = linearGroups(*context_, invocations, groupSize, pipeline.name());
  dispatch(pipeline, bindings, pushConstants, groups.x, groups.y);
}

void Sequence::dispatchIndirect(const Pipeline& pipeline, const std::vector<Binding>& bindings,
                                std::span<const std::byte> pushConstants, const Buffer& args,
                                uint64_t offset) {
  requireRecording("dispatchIndirect");
  if (offset % 4 != 0 || offset + sizeof(VkDispatchIndirectCommand) > args.size())
    throw GpuError(pipeline.name() + ": indirect arguments at byte " + std::to_string(offset) + " of " +
                   args.name() + " (" + std::to_string(args.size()) + " bytes)");
  noteFrameParameters(reads(args));
  beginDispatch(pipeline, bindings, pushConstants);
  for (const Slot& slot : slots_) vkCmdDispatchIndirect(slot.commands, args.handle(), offset);
}

void Sequence::render(const RenderTargets& targets, std::span<const Draw> draws) {
  requireRecording("render");
  const Image* first = targets.colors.empty() ? targets.depth : targets.colors.front();
  if (!first) throw GpuError("render: no colour or depth target");
  const uint32_t width = first->desc().width, height = first->desc().height;

  for (const Draw& draw : draws)
    if (const auto& a = draw.area;
        a && (a->offset.x < 0 || a->offset.y < 0 || a->extent.width == 0 || a->extent.height == 0 ||
              a->offset.x + a->extent.width > width || a->offset.y + a->extent.height > height))
      throw GpuError(draw.pipeline->name() + ": draw area lies outside the render targets");

  Touch touch;
  for (const Image* color : targets.colors) addTouch(touch, readsWrites(*color));
  if (targets.depth) addTouch(touch, readsWrites(*targets.depth));
  for (const Draw& draw : draws) {
    for (const Binding& b : draw.bindings) {
      addTouch(touch, b);
      noteFrameParameters(b);
    }
    if (draw.vertices) addTouch(touch, reads(*draw.vertices));
    if (draw.indices) addTouch(touch, reads(*draw.indices));
  }
  barrierIfHazard(touch);

  VkClearValue clearColor{};
  if (targets.clearColor)
    std::copy(targets.clearColor->begin(), targets.clearColor->end(), clearColor.color.float32);
  std::vector<VkRenderingAttachmentInfo> colors;
  for (const Image* color : targets.colors)
    colors.push_back(attachment(*color, targets.clearColor.has_value(), clearColor));
  VkClearValue clearDepth{};
  clearDepth.depthStencil.depth = targets.clearDepth.value_or(1.0f);
  VkRenderingAttachmentInfo depth{};
  if (targets.depth) depth = attachment(*targets.depth, targets.clearDepth.has_value(), clearDepth);

  VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
  info.renderArea = {{0, 0}, {width, height}};
  info.layerCount = 1;
  info.colorAttachmentCount = static_cast<uint32_t>(colors.size());
  info.pColorAttachments = colors.data();
  info.pDepthAttachment = targets.depth ? &depth : nullptr;
  for (const Slot& slot : slots_) {
    vkCmdBeginRendering(slot.commands, &info);
    for (const Draw& draw : draws) recordDraw(*context_, slot.commands, draw, {width, height});
    vkCmdEndRendering(slot.commands);
  }
}

void Sequence::fill(const Buffer& buffer, uint32_t word) {
  requireRecording("fill");
  Touch touch;
  addTouch(touch, writes(buffer));
  barrierIfHazard(touch);
  for (const Slot& slot : slots_) vkCmdFillBuffer(slot.commands, buffer.handle(), 0, VK_WHOLE_SIZE, word);
}

void Sequence::copy(const Buffer& source, const Buffer& destination) {
  requireRecording("copy");
  if (destination.size() < source.size())
    throw GpuError("copy from " + source.name() + " into the smaller " + destination.name());
  Touch touch;
  addTouch(touch, reads(source));
  addTouch(touch, writes(destination));
  barrierIfHazard(touch);
  VkBufferCopy region{0, 0, source.size()};
  for (const Slot& slot : slots_)
    vkCmdCopyBuffer(slot.commands, source.handle(), destination.handle(), 1, &region);
}

void Sequence::finish() {
  requireRecording("finish");
  if (stageOpen_) throw GpuError("stage '" + stageNames_.back() + "' was not ended");
  for (const Slot& slot : slots_) SIXWAY_VK(vkEndCommandBuffer(slot.commands));
  finished_ = true;
}

void Sequence::addReadback(const Buffer& source) {
  readbacks_.push_back({source.handle(), source.size(), source.name(), {}});
}

std::span<const std::byte> Sequence::readback(const Buffer& source, uint64_t frame) const {
  for (const Readback& r : readbacks_)
    if (r.source == source.handle() && !r.slots.empty()) {
      const Buffer& slot = r.slots[frame % r.slots.size()];
      return {static_cast<const std::byte*>(slot.mapped()), r.bytes};
    }
  throw GpuError(source.name() + ": not a readback of a recorded frame of this sequence");
}

void Sequence::record(VkCommandBuffer commands, uint64_t frame) {
  recordInto(commands, frame, true);
}

void Sequence::recordInto(VkCommandBuffer commands, uint64_t frame, bool withReadbacks) {
  if (!finished_) finish();
  const Slot& slot = slots_[frame % slots_.size()];
  if (slot.executions++ > 0) collectTimes(slot, false);  // its last frame's: complete by the contract
  // The host slots of frames in flight, made with the first recorded frame (submit() needs none), before
  // anything goes into the caller's command buffer: an allocation that fails leaves nothing half-recorded.
  if (withReadbacks)
    for (Readback& r : readbacks_)
      for (uint32_t i = uint32_t(r.slots.size()); i <= context_->framesInFlight(); ++i)
        r.slots.emplace_back(*context_, r.bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryKind::HostReadback,
                             r.name + " (readback)");
  recordFullBarrier(commands);  // after the caller's earlier work, and before our last frame's reads end
  if (!frameParameters_.empty()) {
    for (const FrameParameters& f : frameParameters_)
      recordBufferUpdate(commands, f.buffer, f.values, f.bytes);
    recordFullBarrier(commands);
  }
  vkCmdExecuteCommands(commands, 1, &slot.commands);
  recordFullBarrier(commands);
  if (!withReadbacks || readbacks_.empty()) return;
  for (Readback& r : readbacks_) {
    VkBufferCopy region{0, 0, r.bytes};
    vkCmdCopyBuffer(commands, r.source, r.slots[frame % r.slots.size()].handle(), 1, &region);
  }
  VkMemoryBarrier2 toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  toHost.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
  toHost.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
  toHost.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
  toHost.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.memoryBarrierCount = 1;
  dependency.pMemoryBarriers = &toHost;
  vkCmdPipelineBarrier2(commands, &dependency);
}

void Sequence::submit() {
  if (context_->externalSubmit()) {  // an engine's device whose engine runs one-time work itself
    context_->externalSubmit()(
        [&](VkCommandBuffer commands) { recordInto(commands, submissions_++, false); });
    collectTimes(slots_[(submissions_ - 1) % slots_.size()], true);
    return;
  }
  SIXWAY_VK(vkResetCommandBuffer(primary_, 0));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  SIXWAY_VK(vkBeginCommandBuffer(primary_, &begin));
  recordInto(primary_, submissions_++, false);
  SIXWAY_VK(vkEndCommandBuffer(primary_));
  VkSubmitInfo submitInfo{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submitInfo.commandBufferCount = 1;
  submitInfo.pCommandBuffers = &primary_;
  SIXWAY_VK(vkResetFences(context_->device(), 1, &fence_));
  SIXWAY_VK(vkQueueSubmit(context_->queue(), 1, &submitInfo, fence_));
  context_->countHostWait();
  SIXWAY_VK(vkWaitForFences(context_->device(), 1, &fence_, VK_TRUE, UINT64_MAX));
  collectTimes(slots_[(submissions_ - 1) % slots_.size()], true);
}

const std::vector<StageTime>& Sequence::timesOfFrame(uint64_t frame) {
  collectTimes(slots_[frame % slots_.size()], false);
  return times_;
}

void Sequence::collectTimes(const Slot& slot, bool wait) {
  if (wait) times_.clear();
  if (!slot.queries || stageNames_.empty()) return;
  std::vector<uint64_t> ticks(2 * stageNames_.size());
  const VkResult result =
      vkGetQueryPoolResults(context_->device(), slot.queries, 0, static_cast<uint32_t>(ticks.size()),
                            ticks.size() * sizeof(uint64_t), ticks.data(), sizeof(uint64_t),
                            VK_QUERY_RESULT_64_BIT | (wait ? VK_QUERY_RESULT_WAIT_BIT : 0));
  if (result == VK_NOT_READY) return;  // not executed yet, or still running: keep the last times
  SIXWAY_VK(result);
  times_.clear();
  const uint32_t bits = context_->capabilities().timestampValidBits;
  const uint64_t mask = bits >= 64 ? ~0ull : (1ull << bits) - 1;
  for (size_t i = 0; i < stageNames_.size(); ++i) {
    const uint64_t elapsed = ((ticks[2 * i + 1] & mask) - (ticks[2 * i] & mask)) & mask;
    times_.push_back({stageNames_[i], double(elapsed) * context_->capabilities().timestampPeriodNs * 1e-6});
  }
}

}  // namespace sixway::gpu
