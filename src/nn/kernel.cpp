#include "nn/kernel.h"

#include <algorithm>

#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"

namespace sixway::nn {

PipelinePool::PipelinePool(const gpu::Context& context, const gpu::PipelineCache& cache)
    : context_(&context), cache_(&cache) {}

PipelinePool::~PipelinePool() = default;

const gpu::Pipeline& PipelinePool::get(const gpu::ComputePipelineDesc& desc) {
  std::string key = desc.shader + "|" + std::to_string(desc.pushConstantBytes) + "|";
  for (gpu::BindingType type : desc.bindings) key += std::to_string(int(type)) + ",";
  const VkSpecializationInfo spec = desc.spec.info();
  const auto* words = static_cast<const uint32_t*>(spec.pData);
  for (uint32_t i = 0; i < spec.mapEntryCount; ++i) {
    key += '|';
    key += std::to_string(spec.pMapEntries[i].constantID);
    key += '=';
    key += std::to_string(words[spec.pMapEntries[i].offset / sizeof(uint32_t)]);
  }
  std::unique_ptr<gpu::Pipeline>& pipeline = pipelines_[key];
  if (!pipeline) pipeline = std::make_unique<gpu::Pipeline>(*context_, *cache_, desc);
  return *pipeline;
}

std::string shaderName(const char* name, Precision precision) {
  return std::string("nn/") + name + ".comp" + (precision == Precision::Fp16 ? ":NN_FP16" : "");
}

gpu::Buffer uniformBuffer(const gpu::Context& context, const std::vector<float>& values, std::string name) {
  gpu::Buffer buffer(context, values.size() * sizeof(float),
                     VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                     gpu::MemoryKind::Device, std::move(name));
  buffer.upload(values);
  return buffer;
}

Tiling resolveTiling(Tiling requested, const gpu::Context& context) {
  const bool matrices = bool(context.capabilities().cooperativeMatrix);
  if (requested == Tiling::Matrix && !matrices)
    throw gpu::GpuError(std::string("matrix tiling: ") + context.properties().deviceName +
                        " has no cooperative matrices sixway can use (VK_NV_cooperative_matrix with fp16 "
                        "inputs, fp32 sums and subgroups of 32)");
  if (requested != Tiling::Device) return requested;
  if (context.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) return Tiling::Blocks;
  return matrices ? Tiling::Matrix : Tiling::Pixels;
}

const char* tilingName(Tiling tiling) {
  switch (tiling) {
    case Tiling::Device:
      return "device";
    case Tiling::Blocks:
      return "blocks";
    case Tiling::Pixels:
      return "pixels";
    case Tiling::Matrix:
      return "matrix";
  }
  return "?";
}

uint32_t maxUniformBytes(const gpu::Context& context) {
  return std::min<uint32_t>(context.limits().maxUniformBufferRange, 65536);
}

}  // namespace sixway::nn
