#include "gpu/pipeline.h"

#include <sixway/shader_registry.h>
#include <bit>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <map>
#include <string_view>

#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/spirv_reflect.h"
#include "platform/platform.h"
#include "gpu/vulkan_functions.h"

namespace sixway::gpu {
namespace {

VkDescriptorType descriptorType(BindingType type) {
  switch (type) {
    case BindingType::StorageBuffer:
      return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case BindingType::UniformBuffer:
      return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case BindingType::StorageImage:
      return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    case BindingType::SampledImage:
      return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    case BindingType::StorageTexelBuffer:
      return VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
  }
  return VK_DESCRIPTOR_TYPE_MAX_ENUM;
}

// A shader module that lives as long as pipeline creation needs it.
class ShaderModule {
 public:
  ShaderModule(const Context& context, const std::string& shader)
      : device_(context.device()), allocator_(context.allocator()) {
    auto words = shaders::spirv(shader);
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = words.size_bytes();
    info.pCode = words.data();
    SIXWAY_VK(vkCreateShaderModule(device_, &info, allocator_, &module_));
  }
  ~ShaderModule() { vkDestroyShaderModule(device_, module_, allocator_); }
  ShaderModule(const ShaderModule&) = delete;
  ShaderModule& operator=(const ShaderModule&) = delete;
  VkShaderModule handle() const { return module_; }

 private:
  VkDevice device_;
  const VkAllocationCallbacks* allocator_;
  VkShaderModule module_ = VK_NULL_HANDLE;
};

// Throws GpuError unless each constant in `spec` is declared by at least one of `stages` (a graphics pipeline
// applies the same constants to both) with the host's name and type: what keeps the ids of a family's GLSL
// include and of its C++ header (spec_id.h) the same.
void checkSpecConstants(const SpecConstants& spec, std::initializer_list<std::string_view> stages) {
  std::vector<std::map<uint32_t, ShaderSpecConstant>> declared;
  for (std::string_view shader : stages) declared.push_back(reflectSpecConstants(shaders::spirv(shader)));
  for (const SpecConstants::Entry& host : spec.entries()) {
    const std::string id = std::to_string(host.id.id), hostName(host.id.name);
    bool found = false;
    for (size_t stage = 0; stage < declared.size(); ++stage) {
      const auto constant = declared[stage].find(host.id.id);
      if (constant == declared[stage].end()) continue;
      found = true;
      const ShaderSpecConstant& inShader = constant->second;
      const std::string where =
          "shader " + std::string(stages.begin()[stage]) + ": specialization constant " + id;
      if (!inShader.name.empty() && inShader.name != host.id.name)
        throw GpuError(where + " is " + inShader.name + ", set by the host as " + hostName);
      if (inShader.type != host.type)
        throw GpuError(where + " (" + hostName + ") is " + std::string(specTypeName(inShader.type)) +
                       " in the shader, set by the host as " + std::string(specTypeName(host.type)));
    }
    if (!found) {
      std::string names;
      for (std::string_view shader : stages) names += (names.empty() ? "" : " and ") + std::string(shader);
      throw GpuError((stages.size() == 1 ? "shader " + names + " has" : "shaders " + names + " have") +
                     " no specialization constant " + id + " (set by the host as " + hostName + ")");
    }
  }
}

// The largest pipeline cache read: a driver's cache of every sixway pipeline is a few MiB.
constexpr uint64_t kMaxPipelineCacheBytes = uint64_t(256) << 20;

void notePipelineCache(const Context& context, const std::filesystem::path& file,
                       const std::string& problem) {
  context.note("pipeline cache " + file.string() + " " + problem + "; starting without it");
}

// The cache file's bytes; empty when there is none. Anything but a regular file of at most
// kMaxPipelineCacheBytes (a FIFO, which would block, a directory, a device that never ends) is left unread
// with one note: a bad cache costs the compile time it would have saved, never the command.
std::vector<char> readCacheFile(const Context& context, const std::filesystem::path& file) {
  platform::FileRead read = platform::readRegularFile(file, kMaxPipelineCacheBytes);
  if (!read.problem.empty()) notePipelineCache(context, file, read.problem);
  return std::move(read.bytes);
}

// Whether saving may put a file at `file`: nothing there yet, or a regular file (through links).
bool replaceable(const std::filesystem::path& file) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(file, error);
  return status.type() == std::filesystem::file_type::not_found || std::filesystem::is_regular_file(status);
}

}  // namespace

SpecConstants& SpecConstants::setWord(SpecId id, SpecType type, uint32_t word) {
  entries_.push_back({id, type});
  mapEntries_.push_back({id.id, static_cast<uint32_t>(words_.size() * sizeof(uint32_t)), sizeof(uint32_t)});
  words_.push_back(word);
  return *this;
}
SpecConstants& SpecConstants::set(SpecId id, uint32_t value) {
  return setWord(id, SpecType::Uint, value);
}
SpecConstants& SpecConstants::set(SpecId id, int32_t value) {
  return setWord(id, SpecType::Int, std::bit_cast<uint32_t>(value));
}
SpecConstants& SpecConstants::set(SpecId id, float value) {
  return setWord(id, SpecType::Float, std::bit_cast<uint32_t>(value));
}
SpecConstants& SpecConstants::set(SpecId id, bool value) {
  return setWord(id, SpecType::Bool, value ? 1u : 0u);
}

VkSpecializationInfo SpecConstants::info() const {
  VkSpecializationInfo info{};
  info.mapEntryCount = static_cast<uint32_t>(mapEntries_.size());
  info.pMapEntries = mapEntries_.data();
  info.dataSize = words_.size() * sizeof(uint32_t);
  info.pData = words_.data();
  return info;
}

std::filesystem::path defaultPipelineCacheFile(const Context& context) {
  std::filesystem::path base;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    base = xdg;
  else if (const char* home = std::getenv("HOME"); home && *home)
    base = std::filesystem::path(home) / ".cache";
  else
    return {};
  char uuid[2 * VK_UUID_SIZE + 1];
  for (uint32_t i = 0; i < VK_UUID_SIZE; ++i)
    std::snprintf(uuid + 2 * i, 3, "%02x", context.properties().pipelineCacheUUID[i]);
  return base / "sixway" / ("pipelines-" + std::string(uuid) + ".bin");
}

PipelineCache::PipelineCache(const Context& context, std::filesystem::path file)
    : context_(&context), file_(std::move(file)) {
  if (context.externalPipelineCache()) {
    cache_ = context.externalPipelineCache();
    owned_ = false;
    file_.clear();
    return;
  }
  // The driver checks the header (vendor, device, cache UUID) and ignores data that does not match.
  std::vector<char> data = file_.empty() ? std::vector<char>{} : readCacheFile(context, file_);
  VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  info.initialDataSize = data.size();
  info.pInitialData = data.empty() ? nullptr : data.data();
  if (vkCreatePipelineCache(context.device(), &info, context.allocator(), &cache_) != VK_SUCCESS) {
    info.initialDataSize = 0;  // a corrupt cache file is not an error: start empty
    info.pInitialData = nullptr;
    SIXWAY_VK(vkCreatePipelineCache(context.device(), &info, context.allocator(), &cache_));
  }
}

PipelineCache::~PipelineCache() {
  if (!owned_) return;
  try {
    save();
  } catch (const std::exception& e) {
    context_->note(std::string("pipeline cache not saved: ") + e.what());
  }
  vkDestroyPipelineCache(context_->device(), cache_, context_->allocator());
}

void PipelineCache::save() const {
  // A directory, FIFO or device where the cache belongs stays as it is (its note came when it was read).
  if (file_.empty() || !replaceable(file_)) return;
  size_t size = 0;
  SIXWAY_VK(vkGetPipelineCacheData(context_->device(), cache_, &size, nullptr));
  std::vector<char> data(size);
  SIXWAY_VK(vkGetPipelineCacheData(context_->device(), cache_, &size, data.data()));
  std::filesystem::create_directories(file_.parent_path());
  // Written under a temporary name, then renamed: a concurrent reader never sees half a file.
  std::filesystem::path temporary = file_;
  temporary += ".tmp" + std::to_string(platform::processId());
  {
    std::ofstream out(temporary, std::ios::binary);
    out.write(data.data(), static_cast<std::streamsize>(size));
    if (!out) throw GpuError("cannot write " + temporary.string());
  }
  std::filesystem::rename(temporary, file_);
}

void Pipeline::createOrRelease(VkResult result) {
  if (result == VK_SUCCESS) return;
  release();  // the destructor does not run when a constructor throws
  throwOnFailure(result, ("creating the pipeline of " + name_).c_str());
}

void Pipeline::release() {
  VkDevice device = context_->device();
  if (pipeline_) vkDestroyPipeline(device, pipeline_, context_->allocator());
  if (layout_) vkDestroyPipelineLayout(device, layout_, context_->allocator());
  if (setLayout_) vkDestroyDescriptorSetLayout(device, setLayout_, context_->allocator());
  pipeline_ = VK_NULL_HANDLE;
  layout_ = VK_NULL_HANDLE;
  setLayout_ = VK_NULL_HANDLE;
}

void Pipeline::createLayout(const std::vector<BindingType>& bindings, uint32_t pushConstantBytes) {
  const VkPhysicalDeviceLimits& limits = context_->limits();
  if (pushConstantBytes > limits.maxPushConstantsSize)
    throw GpuError(name_ + ": " + std::to_string(pushConstantBytes) +
                   " bytes of push constants, the device allows " +
                   std::to_string(limits.maxPushConstantsSize));
  std::vector<VkDescriptorSetLayoutBinding> layoutBindings;
  for (uint32_t i = 0; i < bindings.size(); ++i)
    layoutBindings.push_back({i, descriptorType(bindings[i]), 1, stages_, nullptr});
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  setInfo.bindingCount = static_cast<uint32_t>(layoutBindings.size());
  setInfo.pBindings = layoutBindings.data();
  SIXWAY_VK(vkCreateDescriptorSetLayout(context_->device(), &setInfo, context_->allocator(), &setLayout_));

  VkPushConstantRange range{stages_, 0, pushConstantBytes};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &setLayout_;
  layoutInfo.pushConstantRangeCount = pushConstantBytes ? 1 : 0;
  layoutInfo.pPushConstantRanges = &range;
  createOrRelease(vkCreatePipelineLayout(context_->device(), &layoutInfo, context_->allocator(), &layout_));
}

Pipeline::Pipeline(const Context& context, const PipelineCache& cache, const ComputePipelineDesc& desc)
    : context_(&context),
      name_(desc.shader),
      bindPoint_(VK_PIPELINE_BIND_POINT_COMPUTE),
      stages_(VK_SHADER_STAGE_COMPUTE_BIT),
      bindings_(desc.bindings),
      pushConstantBytes_(desc.pushConstantBytes) {
  checkSpecConstants(desc.spec, {desc.shader});
  ShaderModule module(context, desc.shader);
  createLayout(desc.bindings, desc.pushConstantBytes);
  VkSpecializationInfo spec = desc.spec.info();
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module.handle();
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = desc.spec.empty() ? nullptr : &spec;
  info.layout = layout_;
  createOrRelease(
      vkCreateComputePipelines(context.device(), cache.handle(), 1, &info, context.allocator(), &pipeline_));
}

Pipeline::Pipeline(const Context& context, const PipelineCache& cache, const GraphicsPipelineDesc& desc)
    : context_(&context),
      name_(desc.vertexShader + "+" + desc.fragmentShader),
      bindPoint_(VK_PIPELINE_BIND_POINT_GRAPHICS),
      stages_(VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT),
      bindings_(desc.bindings),
      pushConstantBytes_(desc.pushConstantBytes) {
  checkSpecConstants(desc.spec, {desc.vertexShader, desc.fragmentShader});
  ShaderModule vertex(context, desc.vertexShader);
  ShaderModule fragment(context, desc.fragmentShader);
  createLayout(desc.bindings, desc.pushConstantBytes);
  VkSpecializationInfo spec = desc.spec.info();
  VkPipelineShaderStageCreateInfo shaderStages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                     {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
  shaderStages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  shaderStages[0].module = vertex.handle();
  shaderStages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  shaderStages[1].module = fragment.handle();
  for (auto& stage : shaderStages) {
    stage.pName = "main";
    stage.pSpecializationInfo = desc.spec.empty() ? nullptr : &spec;
  }

  VkVertexInputBindingDescription vertexBinding{0, desc.vertexStride, VK_VERTEX_INPUT_RATE_VERTEX};
  std::vector<VkVertexInputAttributeDescription> attributes;
  for (const VertexAttribute& a : desc.attributes) attributes.push_back({a.location, 0, a.format, a.offset});
  VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vertexInput.vertexBindingDescriptionCount = desc.vertexStride ? 1 : 0;
  vertexInput.pVertexBindingDescriptions = &vertexBinding;
  vertexInput.vertexAttributeDescriptionCount = static_cast<uint32_t>(attributes.size());
  vertexInput.pVertexAttributeDescriptions = attributes.data();

  VkPipelineInputAssemblyStateCreateInfo assembly{
      VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = desc.topology;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = desc.cull;
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = desc.depthTest;
  depth.depthWriteEnable = desc.depthWrite;
  depth.depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL;

  VkPipelineColorBlendAttachmentState blend{};
  blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                         VK_COLOR_COMPONENT_A_BIT;
  if (desc.blend != Blend::None) {
    // Premultiplied "over": dst = src + (1 - src.a) dst (docs/conventions.md, "Shading");
    // additive: dst = src + dst.
    blend.blendEnable = VK_TRUE;
    blend.srcColorBlendFactor = VK_BLEND_FACTOR_ONE;
    blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    blend.dstColorBlendFactor =
        desc.blend == Blend::Additive ? VK_BLEND_FACTOR_ONE : VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    blend.dstAlphaBlendFactor = blend.dstColorBlendFactor;
    blend.colorBlendOp = blend.alphaBlendOp = VK_BLEND_OP_ADD;
  }
  std::vector<VkPipelineColorBlendAttachmentState> blends(desc.colorFormats.size(), blend);
  for (size_t i = desc.colorsWritten; i < blends.size(); ++i) blends[i] = {};  // no blending, nothing written
  VkPipelineColorBlendStateCreateInfo colorBlend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  colorBlend.attachmentCount = static_cast<uint32_t>(blends.size());
  colorBlend.pAttachments = blends.data();

  VkDynamicState dynamicStates[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamicStates;

  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = static_cast<uint32_t>(desc.colorFormats.size());
  rendering.pColorAttachmentFormats = desc.colorFormats.data();
  rendering.depthAttachmentFormat = desc.depthFormat;
  rendering.stencilAttachmentFormat = desc.stencilFormat;

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
  info.stageCount = 2;
  info.pStages = shaderStages;
  info.pVertexInputState = &vertexInput;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &colorBlend;
  info.pDynamicState = &dynamic;
  info.layout = layout_;
  createOrRelease(
      vkCreateGraphicsPipelines(context.device(), cache.handle(), 1, &info, context.allocator(), &pipeline_));
}

Pipeline::~Pipeline() {
  release();
}

}  // namespace sixway::gpu
