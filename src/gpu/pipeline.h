#pragma once
// Compute and graphics pipelines built from the embedded SPIR-V (shaders/), with shapes passed
// as specialization constants and per-dispatch values as push constants. Bindings are pushed
// per dispatch (VK_KHR_push_descriptor): one descriptor set, binding i = the i-th resource.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "gpu/spec_id.h"

namespace sixway::gpu {

class Context;

enum class BindingType { StorageBuffer, UniformBuffer, StorageImage, SampledImage, StorageTexelBuffer };

// Specialization constants: a 32-bit value per constant, in the order they are set. Each remembers the
// name and type the host gave it, so that Pipeline can check them against the shader.
class SpecConstants {
 public:
  struct Entry {
    SpecId id;
    SpecType type;
  };
  SpecConstants& set(SpecId id, uint32_t value);
  SpecConstants& set(SpecId id, int32_t value);
  SpecConstants& set(SpecId id, float value);
  SpecConstants& set(SpecId id, bool value);  // GLSL bool specialization constants are 32-bit
  VkSpecializationInfo info() const;
  bool empty() const { return entries_.empty(); }
  const std::vector<Entry>& entries() const { return entries_; }

 private:
  SpecConstants& setWord(SpecId id, SpecType type, uint32_t word);
  std::vector<Entry> entries_;
  std::vector<VkSpecializationMapEntry> mapEntries_;
  std::vector<uint32_t> words_;
};

// A VkPipelineCache, loaded from and saved to a file so later runs skip shader compilation.
class PipelineCache {
 public:
  // An empty path keeps the cache in memory only (tests). On a context with an external pipeline cache
  // (ExternalDevice::pipelineCache) that cache is used, and no file is read or written.
  PipelineCache(const Context& context, std::filesystem::path file = {});
  ~PipelineCache();  // saves to the file, if there is one
  PipelineCache(const PipelineCache&) = delete;
  PipelineCache& operator=(const PipelineCache&) = delete;
  VkPipelineCache handle() const { return cache_; }
  void save() const;

 private:
  const Context* context_;
  std::filesystem::path file_;
  VkPipelineCache cache_ = VK_NULL_HANDLE;
  bool owned_ = true;
};

// $XDG_CACHE_HOME/sixway (or ~/.cache/sixway)/pipelines-<device uuid>.bin
std::filesystem::path defaultPipelineCacheFile(const Context& context);

struct ComputePipelineDesc {
  std::string shader;  // path below shaders/, e.g. "gpu/reduce_stats.comp"
  std::vector<BindingType> bindings;
  uint32_t pushConstantBytes = 0;
  SpecConstants spec;
};

enum class Blend { None, PremultipliedOver, Additive };

struct VertexAttribute {
  uint32_t location;
  VkFormat format;
  uint32_t offset;
};

struct GraphicsPipelineDesc {
  std::string vertexShader, fragmentShader;
  std::vector<BindingType> bindings;  // visible to both stages
  uint32_t pushConstantBytes = 0;     // visible to both stages
  SpecConstants spec;                 // applied to both stages
  uint32_t vertexStride = 0;          // 0: no vertex buffer (positions made in the shader)
  std::vector<VertexAttribute> attributes;
  std::vector<VkFormat> colorFormats;
  uint32_t colorsWritten = UINT32_MAX;  // the first this many colour attachments are written, the rest masked
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;
  VkFormat stencilFormat = VK_FORMAT_UNDEFINED;  // an engine's rendering with a stencil attachment
  bool depthTest = false, depthWrite = false;
  Blend blend = Blend::None;
  VkCullModeFlags cull = VK_CULL_MODE_NONE;
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
};

class Pipeline {
 public:
  // Throw GpuError, naming the shader and the id, when a specialization constant of `desc` is not one the
  // shader declares with that id, name and type (read from its SPIR-V).
  Pipeline(const Context& context, const PipelineCache& cache, const ComputePipelineDesc& desc);
  Pipeline(const Context& context, const PipelineCache& cache, const GraphicsPipelineDesc& desc);
  ~Pipeline();
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;

  VkPipeline handle() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }
  VkPipelineBindPoint bindPoint() const { return bindPoint_; }
  VkShaderStageFlags stages() const { return stages_; }
  const std::vector<BindingType>& bindings() const { return bindings_; }
  uint32_t pushConstantBytes() const { return pushConstantBytes_; }
  const std::string& name() const { return name_; }

 private:
  void createLayout(const std::vector<BindingType>& bindings, uint32_t pushConstantBytes);
  void createOrRelease(VkResult result);
  void release();

  const Context* context_;
  std::string name_;
  VkPipelineBindPoint bindPoint_;
  VkShaderStageFlags stages_;
  std::vector<BindingType> bindings_;
  uint32_t pushConstantBytes_ = 0;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace sixway::gpu
