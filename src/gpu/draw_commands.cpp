#include "gpu/draw_commands.h"

#include <algorithm>
#include <string>

#include "gpu/buffer.h"
#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/image.h"
#include "gpu/pipeline.h"
#include "gpu/vulkan_functions.h"

namespace sixway::gpu {

void pushBindings(const Context& context, VkCommandBuffer commands, const Pipeline& pipeline,
                  const std::vector<Binding>& bindings) {
  const auto& types = pipeline.bindings();
  if (bindings.size() != types.size())
    throw GpuError(pipeline.name() + ": " + std::to_string(bindings.size()) +
                   " bindings given, the shader has " + std::to_string(types.size()));
  if (bindings.empty()) return;
  std::vector<VkDescriptorBufferInfo> bufferInfos(bindings.size());
  std::vector<VkDescriptorImageInfo> imageInfos(bindings.size());
  std::vector<VkBufferView> texelViews(bindings.size());
  std::vector<VkWriteDescriptorSet> writes(bindings.size());
  for (uint32_t i = 0; i < bindings.size(); ++i) {
    VkWriteDescriptorSet& w = writes[i];
    w = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = i;
    w.descriptorCount = 1;
    const bool wantsBuffer = types[i] == BindingType::StorageBuffer || types[i] == BindingType::UniformBuffer;
    if (auto* t = std::get_if<TexelBufferBinding>(&bindings[i])) {
      if (types[i] != BindingType::StorageTexelBuffer)
        throw GpuError(pipeline.name() + ": binding " + std::to_string(i) + " is not a texel buffer");
      texelViews[i] = t->view->handle();
      w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
      w.pTexelBufferView = &texelViews[i];
    } else if (types[i] == BindingType::StorageTexelBuffer) {
      throw GpuError(pipeline.name() + ": binding " + std::to_string(i) + " expects a texel buffer view");
    } else if (auto* b = std::get_if<BufferBinding>(&bindings[i])) {
      if (!wantsBuffer)
        throw GpuError(pipeline.name() + ": binding " + std::to_string(i) + " expects an image");
      bufferInfos[i] = {b->buffer->handle(), 0, VK_WHOLE_SIZE};
      w.descriptorType = types[i] == BindingType::StorageBuffer ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
                                                                : VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
      w.pBufferInfo = &bufferInfos[i];
    } else {
      const auto& image = std::get<ImageBinding>(bindings[i]);
      if (wantsBuffer)
        throw GpuError(pipeline.name() + ": binding " + std::to_string(i) + " expects a buffer");
      const bool sampled = types[i] == BindingType::SampledImage;
      if (sampled != (image.sampler != nullptr))
        throw GpuError(pipeline.name() + ": binding " + std::to_string(i) +
                       (sampled ? " is sampled and needs a sampler" : " is a storage image, not sampled"));
      imageInfos[i] = {sampled ? image.sampler->handle() : VK_NULL_HANDLE, image.image->view(), image.layout};
      w.descriptorType =
          sampled ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
      w.pImageInfo = &imageInfos[i];
    }
  }
  context.cmdPushDescriptorSet(commands, pipeline.bindPoint(), pipeline.layout(), 0,
                               static_cast<uint32_t>(writes.size()), writes.data());
}

void recordDraw(const Context& context, VkCommandBuffer commands, const Draw& draw, VkExtent2D targets) {
  const uint32_t width = targets.width, height = targets.height;
  if (draw.pipeline->bindPoint() != VK_PIPELINE_BIND_POINT_GRAPHICS)
    throw GpuError(draw.pipeline->name() + ": render needs a graphics pipeline");
  if (draw.pushConstants.size() != draw.pipeline->pushConstantBytes())
    throw GpuError(draw.pipeline->name() + ": push constant size does not match the pipeline");
  const VkRect2D area = draw.area.value_or(VkRect2D{{0, 0}, {width, height}});
  // Negative height: clip-space +y is up and image row 0 is the top, as in the rest of sixway.
  VkViewport viewport{float(area.offset.x),
                      float(area.offset.y + area.extent.height),
                      float(area.extent.width),
                      -float(area.extent.height),
                      0.0f,
                      1.0f};
  vkCmdSetViewport(commands, 0, 1, &viewport);
  vkCmdSetScissor(commands, 0, 1, &area);
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_GRAPHICS, draw.pipeline->handle());
  pushBindings(context, commands, *draw.pipeline, draw.bindings);
  if (!draw.pushConstants.empty())
    vkCmdPushConstants(commands, draw.pipeline->layout(), draw.pipeline->stages(), 0,
                       static_cast<uint32_t>(draw.pushConstants.size()), draw.pushConstants.data());
  if (draw.vertices) {
    VkBuffer buffer = draw.vertices->handle();
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(commands, 0, 1, &buffer, &offset);
  }
  if (draw.indices) {
    vkCmdBindIndexBuffer(commands, draw.indices->handle(), 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(commands, draw.count, draw.instances, 0, 0, 0);
  } else {
    vkCmdDraw(commands, draw.count, draw.instances, 0, 0);
  }
}

void recordBufferUpdate(VkCommandBuffer commands, VkBuffer buffer, const std::byte* values, uint64_t bytes) {
  constexpr uint64_t kMaxUpdate = 65536;  // vkCmdUpdateBuffer's limit per command
  for (uint64_t offset = 0; offset < bytes; offset += kMaxUpdate)
    vkCmdUpdateBuffer(commands, buffer, offset, std::min(kMaxUpdate, bytes - offset), values + offset);
}

void recordParameterUpdates(VkCommandBuffer commands, std::span<const Buffer* const> buffers) {
  for (const Buffer* b : buffers) {
    if (b->kind() != MemoryKind::FrameParameters)
      throw GpuError(b->name() + ": not a frame-parameter buffer");
    recordBufferUpdate(commands, b->handle(), static_cast<const std::byte*>(b->mapped()), b->size());
  }
}

}  // namespace sixway::gpu
