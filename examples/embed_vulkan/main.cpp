// A minimal "engine": it owns its Vulkan instance and device, draws its own scene (a floor and a box) into a
// colour and a depth image, and composites sixway's smoke over it through the public API, headless. What an
// engine does that sixway must follow: its camera is reversed-Z with an infinite far plane and a TAA jitter
// each frame, handed over as view and projection matrices; three frames in flight, each with its own colour
// and depth images in optimal layouts; a frame time that varies (30 and 144 fps, hitches) and the smoke's
// speed does not; its own host allocator and pipeline cache; sixway's one-time work submitted by the engine
// itself. Two smoke instances placed in its world share one network and are drawn back to front: one with
// FrameTargets (sixway moves the images to what it needs and back), one inside the engine's own transparent
// pass (its dynamic rendering, depth read-only), both lit by the engine's sun. Mid-run the window grows (the
// targets are made anew at the new size), the engine's emitter circles and is switched off and on, its
// character (a capsule obstacle) circles through the smoke and a crate (a box) comes and goes, all given by
// the engine each frame. Writes the last frame as a PNG and prints what sixway
// submitted and waited for after the first frame; fails on any validation message. With --own-material,
// instance A is shaded by the engine's own material (material.frag: Unity's six-way formula over sixway's
// lightmaps in the RLT/BBF packing) instead of sixway's composite; --psnr-against compares the PNG with
// another run's.
//   embed_vulkan --scene S.json --weights W.safetensors [--frames N] [--c-api] [--own-material]
//                [--no-validation] [--psnr-against IMAGE --min-psnr DB] --out frame.png
#include <sixway/device.h>
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#include <vulkan/vulkan.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>
#include <glm/mat4x4.hpp>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "smoke_instances.h"

namespace {

void check(VkResult result, const char* call) {
  if (result != VK_SUCCESS)
    throw std::runtime_error(std::string(call) + " failed (" + std::to_string(result) + ")");
}
#define VK(call) check(call, #call)

std::atomic<int> validationMessages{0};

VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                         VkDebugUtilsMessageTypeFlagsEXT,
                                         const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  ++validationMessages;
  std::fprintf(stderr, "validation: %s\n", data->pMessage);
  return VK_FALSE;
}

std::vector<uint32_t> readSpirv(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::vector<uint32_t> words(size_t(in.tellg()) / 4);
  in.seekg(0);
  in.read(reinterpret_cast<char*>(words.data()), std::streamsize(words.size() * 4));
  return words;
}

struct Options {
  std::string scene, weights, out;
  int frames = 6;
  bool cApi = false;         // sixway through its C API
  bool ownMaterial = false;  // instance A shaded by the engine's material (material.frag)
  bool validate = true;      // off for timing: the layer checks every command sixway records
  std::string psnrAgainst;   // an image to compare the PNG with
  double minPsnr = 0.0;      // dB: below it the run fails
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string key = argv[i];
    if (key == "--c-api" || key == "--own-material" || key == "--no-validation") {
      if (key == "--no-validation")
        o.validate = false;
      else
        (key == "--c-api" ? o.cApi : o.ownMaterial) = true;
      continue;
    }
    if (i + 1 == argc) throw std::runtime_error(key + ": needs a value");
    const std::string value = argv[++i];
    if (key == "--scene")
      o.scene = value;
    else if (key == "--weights")
      o.weights = value;
    else if (key == "--out")
      o.out = value;
    else if (key == "--frames")
      o.frames = std::stoi(value);
    else if (key == "--psnr-against")
      o.psnrAgainst = value;
    else if (key == "--min-psnr")
      o.minPsnr = std::stod(value);
    else
      throw std::runtime_error("unknown option " + key);
  }
  if (o.scene.empty() || o.weights.empty() || o.out.empty() || o.frames < 1)
    throw std::runtime_error(
        "usage: embed_vulkan --scene S.json --weights W.safetensors [--frames N] [--c-api] [--own-material] "
        "[--no-validation] [--psnr-against IMAGE --min-psnr DB] --out F.png");
  return o;
}

// The engine's Vulkan objects: instance (with validation unless it is timed), one device, one queue.
struct Engine {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  std::vector<std::string> extensions;
  std::unique_ptr<sixway::DeviceRequirements> requirements;  // its feature chain was given to vkCreateDevice

  explicit Engine(bool validate) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "embed_vulkan";
    app.apiVersion = VK_API_VERSION_1_3;
    const char* layer = "VK_LAYER_KHRONOS_validation";
    const char* debugUtils = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    // Not the performance hints: sixway keeps its own images in VK_IMAGE_LAYOUT_GENERAL.
    messengerInfo.messageType =
        VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    messengerInfo.pfnUserCallback = onMessage;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, &messengerInfo};
    info.pApplicationInfo = &app;
    info.enabledLayerCount = validate ? 1 : 0;
    info.ppEnabledLayerNames = &layer;
    info.enabledExtensionCount = 1;
    info.ppEnabledExtensionNames = &debugUtils;
    VK(vkCreateInstance(&info, nullptr, &instance));
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    VK(create(instance, &messengerInfo, nullptr, &messenger));

    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance, &count, devices.data());
    for (VkPhysicalDevice candidate : devices) {
      VkPhysicalDeviceProperties properties;
      vkGetPhysicalDeviceProperties(candidate, &properties);
      if (properties.apiVersion < VK_API_VERSION_1_3) continue;
      uint32_t familyCount = 0;
      vkGetPhysicalDeviceQueueFamilyProperties(candidate, &familyCount, nullptr);
      std::vector<VkQueueFamilyProperties> families(familyCount);
      vkGetPhysicalDeviceQueueFamilyProperties(candidate, &familyCount, families.data());
      for (uint32_t f = 0; f < familyCount; ++f)
        if ((families[f].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) ==
            (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) {
          physicalDevice = candidate;
          queueFamily = f;
          break;
        }
      if (physicalDevice) break;
    }
    if (!physicalDevice) throw std::runtime_error("no Vulkan 1.3 device with a graphics and compute queue");

    // The engine's device, with what sixway needs enabled (its features include dynamic rendering,
    // which the engine's own pass uses too).
    requirements = std::make_unique<sixway::DeviceRequirements>(physicalDevice);
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = queueFamily;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;
    VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, requirements->features()};
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    deviceInfo.enabledExtensionCount = uint32_t(requirements->extensions().size());
    deviceInfo.ppEnabledExtensionNames = requirements->extensions().data();
    VK(vkCreateDevice(physicalDevice, &deviceInfo, nullptr, &device));
    vkGetDeviceQueue(device, queueFamily, 0, &queue);
    extensions.assign(requirements->extensions().begin(), requirements->extensions().end());
  }

  ~Engine() {
    if (device) vkDestroyDevice(device, nullptr);
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (messenger) destroy(instance, messenger, nullptr);
    vkDestroyInstance(instance, nullptr);
  }

  uint32_t memoryType(uint32_t bits, VkMemoryPropertyFlags flags) const {
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(physicalDevice, &memory);
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i)
      if ((bits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & flags) == flags) return i;
    throw std::runtime_error("no suitable memory type");
  }
};

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  const Engine* engine = nullptr;

  Image(const Engine& e, uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage,
        VkImageAspectFlags aspect)
      : engine(&e) {
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width, height, 1};
    info.mipLevels = info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.usage = usage;
    VK(vkCreateImage(e.device, &info, nullptr, &image));
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(e.device, image, &requirements);
    VkMemoryAllocateInfo alloc{
        VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, requirements.size,
        e.memoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)};
    VK(vkAllocateMemory(e.device, &alloc, nullptr, &memory));
    VK(vkBindImageMemory(e.device, image, memory, 0));
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = image;
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = format;
    viewInfo.subresourceRange = {aspect, 0, 1, 0, 1};
    VK(vkCreateImageView(e.device, &viewInfo, nullptr, &view));
  }
  ~Image() {
    vkDestroyImageView(engine->device, view, nullptr);
    vkDestroyImage(engine->device, image, nullptr);
    vkFreeMemory(engine->device, memory, nullptr);
  }
};

// Begins the engine's dynamic rendering of one colour and one depth attachment over the whole image.
void beginRendering(VkCommandBuffer cmd, const VkRenderingAttachmentInfo& color,
                    const VkRenderingAttachmentInfo& depth, uint32_t width, uint32_t height) {
  VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
  info.renderArea = {{0, 0}, {width, height}};
  info.layerCount = 1;
  info.colorAttachmentCount = 1;
  info.pColorAttachments = &color;
  info.pDepthAttachment = &depth;
  vkCmdBeginRendering(cmd, &info);
}

// One of the engine's graphics pipelines: the two SPIR-V stages, no vertex input (positions made in the
// shader), dynamic viewport and scissor, one colour and one depth attachment.
VkPipeline enginePipeline(const Engine& e, const char* vertexFile, const char* fragmentFile,
                          VkPipelineLayout layout, const VkPipelineDepthStencilStateCreateInfo& depth,
                          const VkPipelineColorBlendAttachmentState& blend, VkFormat colorFormat,
                          VkFormat depthFormat) {
  VkShaderModule modules[2];
  const char* files[2] = {vertexFile, fragmentFile};
  for (int i = 0; i < 2; ++i) {
    const std::vector<uint32_t> words = readSpirv(files[i]);
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, nullptr, 0, words.size() * 4,
                                  words.data()};
    VK(vkCreateShaderModule(e.device, &info, nullptr, &modules[i]));
  }
  VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr,
                                                0, VK_SHADER_STAGE_VERTEX_BIT, modules[0], "main"},
                                               {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr,
                                                0, VK_SHADER_STAGE_FRAGMENT_BIT, modules[1], "main"}};
  VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo assembly{
      VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineColorBlendStateCreateInfo blendState{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blendState.attachmentCount = 1;
  blendState.pAttachments = &blend;
  VkDynamicState dynamics[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO, nullptr, 0,
                                           2, dynamics};
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachmentFormats = &colorFormat;
  rendering.depthAttachmentFormat = depthFormat;
  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
  info.stageCount = 2;
  info.pStages = stages;
  info.pVertexInputState = &vertexInput;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blendState;
  info.pDynamicState = &dynamic;
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  const VkResult result = vkCreateGraphicsPipelines(e.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
  for (VkShaderModule m : modules) vkDestroyShaderModule(e.device, m, nullptr);
  VK(result);
  return pipeline;
}

// The engine's scene pass: the floor and the box, depth tested, into the colour and depth images.
struct ScenePass {
  const Engine& engine;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
  struct Push {
    glm::mat4 viewProjection;
    glm::vec4 boxCentreHalf;
  };

  ScenePass(const Engine& e, VkFormat colorFormat, VkFormat depthFormat) : engine(e) {
    VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(Push)};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.pushConstantRangeCount = 1;
    layoutInfo.pPushConstantRanges = &range;
    VK(vkCreatePipelineLayout(e.device, &layoutInfo, nullptr, &layout));
    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = depth.depthWriteEnable = VK_TRUE;
    depth.depthCompareOp = VK_COMPARE_OP_GREATER;  // reversed-Z: nearer is larger
    VkPipelineColorBlendAttachmentState blend{};
    blend.colorWriteMask = 0xf;
    pipeline = enginePipeline(e, EMBED_SHADER_DIR "/scene.vert.spv", EMBED_SHADER_DIR "/scene.frag.spv",
                              layout, depth, blend, colorFormat, depthFormat);
  }
  ~ScenePass() {
    vkDestroyPipeline(engine.device, pipeline, nullptr);
    vkDestroyPipelineLayout(engine.device, layout, nullptr);
  }

  void record(VkCommandBuffer cmd, const Image& color, const Image& depth, uint32_t width, uint32_t height,
              const Push& push) const {
    VkRenderingAttachmentInfo colorAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    colorAttachment.imageView = color.view;
    colorAttachment.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colorAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    colorAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    colorAttachment.clearValue.color = {{0.05f, 0.06f, 0.08f, 1.0f}};
    VkRenderingAttachmentInfo depthAttachment = colorAttachment;
    depthAttachment.imageView = depth.view;
    depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depthAttachment.clearValue.depthStencil = {0.0f, 0};  // reversed-Z: 0 is infinitely far
    beginRendering(cmd, colorAttachment, depthAttachment, width, height);
    VkViewport viewport{0, 0, float(width), float(height), 0, 1};
    VkRect2D scissor{{0, 0}, {width, height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(Push), &push);
    vkCmdDraw(cmd, 6 + 36, 1, 0, 0);
    vkCmdEndRendering(cmd);
  }
};

// The engine's own smoke material (material.vert, material.frag) inside its transparent pass: the quad of
// instance A's lightmaps, depth tested against the engine's depth (read-only, reversed-Z), blended "over".
struct MaterialPass {
  const Engine& engine;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkSampler sampler = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;
  VkImageView written[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};  // the views the set holds
  struct Push {
    glm::vec4 clipCorners[4];
    glm::vec4 toLight, irradiance, ambient;
  };

  MaterialPass(const Engine& e, VkFormat colorFormat, VkFormat depthFormat) : engine(e) {
    VkDescriptorSetLayoutBinding bindings[2];
    for (uint32_t b = 0; b < 2; ++b)
      bindings[b] = {b, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    setInfo.bindingCount = 2;
    setInfo.pBindings = bindings;
    VK(vkCreateDescriptorSetLayout(e.device, &setInfo, nullptr, &setLayout));
    VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(Push)};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &setLayout;
    layoutInfo.pushConstantRangeCount = 1;
    layoutInfo.pPushConstantRanges = &range;
    VK(vkCreatePipelineLayout(e.device, &layoutInfo, nullptr, &layout));
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2};
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &size;
    VK(vkCreateDescriptorPool(e.device, &poolInfo, nullptr, &pool));
    VkDescriptorSetAllocateInfo allocate{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO, nullptr, pool, 1,
                                         &setLayout};
    VK(vkAllocateDescriptorSets(e.device, &allocate, &set));
    VkSamplerCreateInfo samplerInfo{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    samplerInfo.magFilter = samplerInfo.minFilter = VK_FILTER_LINEAR;
    samplerInfo.addressModeU = samplerInfo.addressModeV = samplerInfo.addressModeW =
        VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    VK(vkCreateSampler(e.device, &samplerInfo, nullptr, &sampler));

    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = VK_TRUE;  // tested, not written: the depth is read-only in the transparent pass
    depth.depthCompareOp = VK_COMPARE_OP_GREATER_OR_EQUAL;  // reversed-Z
    VkPipelineColorBlendAttachmentState blend{};
    blend.blendEnable = VK_TRUE;  // premultiplied "over"
    blend.srcColorBlendFactor = blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    blend.dstColorBlendFactor = blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    blend.colorBlendOp = blend.alphaBlendOp = VK_BLEND_OP_ADD;
    blend.colorWriteMask = 0xf;
    pipeline = enginePipeline(e, EMBED_SHADER_DIR "/material.vert.spv", EMBED_SHADER_DIR "/material.frag.spv",
                              layout, depth, blend, colorFormat, depthFormat);
  }
  ~MaterialPass() {
    vkDestroyPipeline(engine.device, pipeline, nullptr);
    vkDestroyPipelineLayout(engine.device, layout, nullptr);
    vkDestroyDescriptorPool(engine.device, pool, nullptr);
    vkDestroyDescriptorSetLayout(engine.device, setLayout, nullptr);
    vkDestroySampler(engine.device, sampler, nullptr);
  }

  // Inside the transparent pass: the quad of `maps` seen through `viewProjection`, lit by the sun (toward
  // it, in the world; colour · intensity) in the six-way frame of `view` (x right, y up, z away from the
  // camera), and the ambient radiance.
  void draw(VkCommandBuffer cmd, const PackedLightmaps& maps, const glm::mat4& view,
            const glm::mat4& viewProjection, glm::vec3 sun, glm::vec3 irradiance, glm::vec3 ambient,
            uint32_t width, uint32_t height) {
    if (maps.rlt != written[0] || maps.bbf != written[1]) {  // the renderer's views: the same for its life
      VkDescriptorImageInfo images[2] = {{sampler, maps.rlt, VK_IMAGE_LAYOUT_GENERAL},
                                         {sampler, maps.bbf, VK_IMAGE_LAYOUT_GENERAL}};
      VkWriteDescriptorSet writes[2];
      for (uint32_t b = 0; b < 2; ++b) {
        writes[b] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[b].dstSet = set;
        writes[b].dstBinding = b;
        writes[b].descriptorCount = 1;
        writes[b].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        writes[b].pImageInfo = &images[b];
      }
      vkUpdateDescriptorSets(engine.device, 2, writes, 0, nullptr);
      written[0] = maps.rlt;
      written[1] = maps.bbf;
    }
    Push push{};
    for (int c = 0; c < 4; ++c) push.clipCorners[c] = viewProjection * glm::vec4(maps.corners[c], 1.0f);
    const glm::vec3 right(view[0][0], view[1][0], view[2][0]), up(view[0][1], view[1][1], view[2][1]),
        away(-view[0][2], -view[1][2], -view[2][2]);
    const glm::vec3 d = glm::normalize(sun);
    push.toLight = glm::vec4(glm::dot(d, right), glm::dot(d, up), glm::dot(d, away), 0.0f);
    push.irradiance = glm::vec4(irradiance, 0.0f);
    push.ambient = glm::vec4(ambient, 0.0f);
    VkViewport viewport{0, 0, float(width), float(height), 0, 1};
    VkRect2D scissor{{0, 0}, {width, height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(Push), &push);
    vkCmdDraw(cmd, 6, 1, 0, 0);
  }
};

// Everything before into everything after (the engine's frame graph would be finer).
void fullBarrier(VkCommandBuffer cmd) {
  VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  barrier.srcStageMask = barrier.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  barrier.srcAccessMask = barrier.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.memoryBarrierCount = 1;
  dependency.pMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

// The engine's transparent pass: colour and depth loaded, the depth read-only (sampled by the smoke too).
void beginTransparentPass(VkCommandBuffer cmd, VkImageView color, VkImageView depth, uint32_t width,
                          uint32_t height) {
  VkRenderingAttachmentInfo colorAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  colorAttachment.imageView = color;
  colorAttachment.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  colorAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  colorAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  VkRenderingAttachmentInfo depthAttachment = colorAttachment;
  depthAttachment.imageView = depth;
  depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  depthAttachment.storeOp = VK_ATTACHMENT_STORE_OP_NONE;
  beginRendering(cmd, colorAttachment, depthAttachment, width, height);
}

// The engine's layout changes: `from` UNDEFINED discards the contents (each frame clears them anyway).
void changeLayout(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                  VkImageLayout to) {
  VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  barrier.srcStageMask = barrier.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  barrier.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  barrier.oldLayout = from;
  barrier.newLayout = to;
  barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {aspect, 0, 1, 0, 1};
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

// The engine's host allocator, handed to sixway for its Vulkan objects: counts what is live.
struct HostAllocator {
  std::mutex mutex;
  std::map<void*, size_t> live;
  VkAllocationCallbacks callbacks{};

  HostAllocator() {
    callbacks.pUserData = this;
    callbacks.pfnAllocation = [](void* user, size_t size, size_t alignment, VkSystemAllocationScope) {
      return static_cast<HostAllocator*>(user)->allocate(size, alignment);
    };
    callbacks.pfnReallocation = [](void* user, void* old, size_t size, size_t alignment,
                                   VkSystemAllocationScope) -> void* {
      auto* self = static_cast<HostAllocator*>(user);
      if (!old) return self->allocate(size, alignment);
      void* fresh = size ? self->allocate(size, alignment) : nullptr;
      if (fresh) std::memcpy(fresh, old, std::min(size, self->sizeOf(old)));
      if (fresh || size == 0) self->release(old);
      return fresh;
    };
    callbacks.pfnFree = [](void* user, void* memory) { static_cast<HostAllocator*>(user)->release(memory); };
  }
  void* allocate(size_t size, size_t alignment) {
    void* memory = std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment);
    std::lock_guard lock(mutex);
    if (memory) live[memory] = size;
    return memory;
  }
  size_t sizeOf(void* memory) {
    std::lock_guard lock(mutex);
    return live.at(memory);
  }
  void release(void* memory) {
    if (!memory) return;
    {
      std::lock_guard lock(mutex);
      live.erase(memory);
    }
    std::free(memory);
  }
};

// One frame in flight's colour and depth images, at the window's size.
struct FrameImages {
  Image color, depth;
  uint32_t width, height;
  bool fresh = true;  // not yet in a layout of the engine's

  FrameImages(const Engine& e, uint32_t w, uint32_t h, VkFormat colorFormat, VkFormat depthFormat)
      : color(e, w, h, colorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
              VK_IMAGE_ASPECT_COLOR_BIT),
        depth(e, w, h, depthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
              VK_IMAGE_ASPECT_DEPTH_BIT),
        width(w),
        height(h) {}
};

float toSrgb(float linear) {
  linear = std::clamp(linear, 0.0f, 1.0f);
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

// The engine's projection: 45° vertically, reversed-Z with an infinite far plane (depth = near / w, as
// Unreal's), NDC y = −1 at the top row (a positive-height viewport), and this frame's TAA jitter: a Halton
// (2, 3) point in the pixel, as a clip-space offset in the z column.
glm::mat4 jitteredProjection(uint64_t frame, uint32_t width, uint32_t height) {
  constexpr float kNear = 0.1f;
  const float f = 1.0f / std::tan(0.5f * glm::radians(45.0f));
  glm::mat4 p(0.0f);
  p[0][0] = f * float(height) / float(width);
  p[1][1] = -f;
  p[2][3] = -1.0f;
  p[3][2] = kNear;
  auto halton = [](uint64_t i, uint64_t base) {
    float value = 0.0f, scale = 1.0f;
    for (uint64_t n = i + 1; n > 0; n /= base) value += (scale /= float(base)) * float(n % base);
    return value;
  };
  p[2][0] += (halton(frame, 2) - 0.5f) * 2.0f / float(width);
  p[2][1] += (halton(frame, 3) - 0.5f) * 2.0f / float(height);
  return p;
}

// The engine's frame time: mostly 30 fps, every other frame 144 fps, every fifth a hitch of 80 ms.
double frameSeconds(uint64_t frame) {
  if (frame % 5 == 4) return 0.08;
  return frame % 2 == 0 ? 1.0 / 30.0 : 1.0 / 144.0;
}

// The engine's command buffers, fences and the one-time work it runs for sixway.
struct FrameLoop {
  static constexpr uint32_t kFramesInFlight = 3;
  const Engine& engine;
  VkCommandPool pool = VK_NULL_HANDLE;
  std::array<VkCommandBuffer, kFramesInFlight + 1> commands{};  // the last: one-time work and the readback
  std::array<VkFence, kFramesInFlight + 1> fences{};
  uint64_t oneTimeJobs = 0;  // sixway's one-time work the engine submitted

  explicit FrameLoop(const Engine& e) : engine(e) {
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = e.queueFamily;
    VK(vkCreateCommandPool(e.device, &poolInfo, nullptr, &pool));
    VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, pool,
                                          VK_COMMAND_BUFFER_LEVEL_PRIMARY, uint32_t(commands.size())};
    VK(vkAllocateCommandBuffers(e.device, &allocInfo, commands.data()));
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, nullptr, VK_FENCE_CREATE_SIGNALED_BIT};
    for (VkFence& f : fences) VK(vkCreateFence(e.device, &fenceInfo, nullptr, &f));
  }
  ~FrameLoop() {
    vkDeviceWaitIdle(engine.device);
    for (VkFence f : fences) vkDestroyFence(engine.device, f, nullptr);
    vkDestroyCommandPool(engine.device, pool, nullptr);
  }
  // Waits for the slot's previous submission and begins its command buffer.
  VkCommandBuffer begin(size_t slot) {
    VK(vkWaitForFences(engine.device, 1, &fences[slot], VK_TRUE, UINT64_MAX));
    VK(vkResetFences(engine.device, 1, &fences[slot]));
    VK(vkResetCommandBuffer(commands[slot], 0));
    VkCommandBufferBeginInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK(vkBeginCommandBuffer(commands[slot], &info));
    return commands[slot];
  }
  void submit(size_t slot) {
    VK(vkEndCommandBuffer(commands[slot]));
    VkSubmitInfo info{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    info.commandBufferCount = 1;
    info.pCommandBuffers = &commands[slot];
    VK(vkQueueSubmit(engine.queue, 1, &info, fences[slot]));
  }
  void waitAll() {
    VK(vkWaitForFences(engine.device, uint32_t(fences.size()), fences.data(), VK_TRUE, UINT64_MAX));
  }
  // EngineDevice::submitAndWait: sixway's one-time work in the engine's command buffer, on its queue.
  void oneTime(const std::function<void(VkCommandBuffer)>& record) {
    VkCommandBuffer cmd = begin(kFramesInFlight);
    record(cmd);
    submit(kFramesInFlight);
    VK(vkWaitForFences(engine.device, 1, &fences[kFramesInFlight], VK_TRUE, UINT64_MAX));
    ++oneTimeJobs;
  }
};

// The colour image as an sRGB PNG (it is in TRANSFER_SRC_OPTIMAL, where sixway left it).
bool writePng(const Engine& engine, FrameLoop& loop, const FrameImages& images, const std::string& path) {
  VkBufferCreateInfo bufferInfo{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bufferInfo.size = uint64_t(images.width) * images.height * 8;
  bufferInfo.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  VkBuffer readback;
  VK(vkCreateBuffer(engine.device, &bufferInfo, nullptr, &readback));
  VkMemoryRequirements requirements;
  vkGetBufferMemoryRequirements(engine.device, readback, &requirements);
  VkMemoryAllocateInfo alloc{
      VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, requirements.size,
      engine.memoryType(requirements.memoryTypeBits,
                        VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT)};
  VkDeviceMemory readbackMemory;
  VK(vkAllocateMemory(engine.device, &alloc, nullptr, &readbackMemory));
  VK(vkBindBufferMemory(engine.device, readback, readbackMemory, 0));
  const size_t slot = FrameLoop::kFramesInFlight;
  VkCommandBuffer cmd = loop.begin(slot);
  fullBarrier(cmd);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {images.width, images.height, 1};
  vkCmdCopyImageToBuffer(cmd, images.color.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback, 1, &region);
  fullBarrier(cmd);
  loop.submit(slot);
  loop.waitAll();
  void* mapped;
  VK(vkMapMemory(engine.device, readbackMemory, 0, VK_WHOLE_SIZE, 0, &mapped));
  std::vector<uint8_t> srgb(size_t(images.width) * images.height * 4);
  const auto* halves = static_cast<const uint16_t*>(mapped);
  for (size_t i = 0; i < srgb.size(); ++i) {
    const float value = glm::unpackHalf1x16(halves[i]);
    srgb[i] = uint8_t(std::lround(255.0f * (i % 4 == 3 ? std::clamp(value, 0.0f, 1.0f) : toSrgb(value))));
  }
  vkUnmapMemory(engine.device, readbackMemory);
  vkDestroyBuffer(engine.device, readback, nullptr);
  vkFreeMemory(engine.device, readbackMemory, nullptr);
  return stbi_write_png(path.c_str(), int(images.width), int(images.height), 4, srgb.data(),
                        int(images.width) * 4) != 0;
}

// The scene file's constant ambient radiance (its ambient.color; none: black): the engine's material adds
// what sixway's shading adds for the scene.
glm::vec3 sceneAmbient(const std::string& scene) {
  std::ifstream in(scene);
  const nlohmann::json json = nlohmann::json::parse(in);
  if (!json.contains("ambient") || !json["ambient"].contains("color")) return glm::vec3(0.0f);
  const auto& c = json["ambient"]["color"];
  return glm::vec3(c[0].get<float>(), c[1].get<float>(), c[2].get<float>());
}

// PSNR (dB) of two 8-bit PNGs of one size over their RGB values.
double psnr(const std::string& a, const std::string& b) {
  int width[2], height[2], channels;
  unsigned char* pixels[2] = {stbi_load(a.c_str(), &width[0], &height[0], &channels, 4),
                              stbi_load(b.c_str(), &width[1], &height[1], &channels, 4)};
  const bool same = pixels[0] && pixels[1] && width[0] == width[1] && height[0] == height[1];
  double sum = 0.0;
  for (size_t i = 0; same && i < size_t(width[0]) * height[0] * 4; ++i)
    if (i % 4 != 3) sum += std::pow(double(pixels[0][i]) - pixels[1][i], 2.0);
  stbi_image_free(pixels[0]);
  stbi_image_free(pixels[1]);
  if (!same) throw std::runtime_error(b + ": cannot be read, or its size is not " + a + "'s");
  const double mse = sum / (3.0 * width[0] * height[0]);
  return mse == 0.0 ? INFINITY : 10.0 * std::log10(255.0 * 255.0 / mse);
}

// Host time of sixway's calls, per call: on the first frame (which records sixway's passes and makes their
// uploads), on the frame after the resize (new targets), and the mean over the other frames.
struct HostTimes {
  struct Call {
    double first = 0.0, resized = 0.0, steadySum = 0.0, steadyMax = 0.0;
  };
  std::map<std::string, Call> calls;
  uint64_t steadyFrames = 0;

  template <class Work>
  void time(const std::string& call, uint64_t frame, uint64_t resizeFrame, Work&& work) {
    // The calling thread's CPU time: on lavapipe the "GPU" runs on the same cores, so wall time would count
    // the earlier frames' GPU work too.
    timespec before, after;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &before);
    work();
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &after);
    const double ms =
        1e3 * double(after.tv_sec - before.tv_sec) + 1e-6 * double(after.tv_nsec - before.tv_nsec);
    Call& c = calls[call];
    (frame == 0 ? c.first : frame == resizeFrame ? c.resized : c.steadySum) += ms;
    if (frame != 0 && frame != resizeFrame) c.steadyMax = std::max(c.steadyMax, ms);
  }
  void print() const {
    std::printf(
        "sixway's host CPU time per frame, ms (first frame / after the resize / mean and most of the %llu "
        "others):\n",
        static_cast<unsigned long long>(steadyFrames));
    for (const auto& [call, c] : calls)
      std::printf("  %-26s %8.2f %8.2f %8.3f %8.2f\n", call.c_str(), c.first, c.resized,
                  c.steadySum / double(std::max<uint64_t>(steadyFrames, 1)), c.steadyMax);
  }
};

int run(const Options& options) {
  constexpr uint32_t kFramesInFlight = FrameLoop::kFramesInFlight;
  constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT, kDepthFormat = VK_FORMAT_D32_SFLOAT;
  Engine engine(options.validate);
  ScenePass scenePass(engine, kColorFormat, kDepthFormat);
  FrameLoop loop(engine);
  HostAllocator allocator;
  VkPipelineCache pipelineCache;
  VkPipelineCacheCreateInfo cacheInfo{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  VK(vkCreatePipelineCache(engine.device, &cacheInfo, nullptr, &pipelineCache));

  // sixway on the engine's device: its allocator, pipeline cache, Vulkan functions and one-time submissions.
  SmokeSetup setup{engine.instance, engine.physicalDevice, engine.device, engine.queue, engine.queueFamily,
                   engine.extensions, engine.requirements->features(), kFramesInFlight,
                   [&](const std::function<void(VkCommandBuffer)>& record) { loop.oneTime(record); },
                   &allocator.callbacks, pipelineCache, vkGetInstanceProcAddr, options.scene, options.weights,
                   kColorFormat, kDepthFormat,
                   // B behind A to the left, turned.
                   glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(-0.9f, 0.0f, -1.0f)),
                               glm::radians(40.0f), glm::vec3(0.0f, 1.0f, 0.0f)),
                   options.ownMaterial,
                   // The engine's sun: the smoke and its own material are lit by it.
                   glm::normalize(glm::vec3(0.3f, 1.0f, 0.4f)), glm::vec3(3.0f)};
  std::optional<MaterialPass> material;
  if (options.ownMaterial) material.emplace(engine, kColorFormat, kDepthFormat);
  const glm::vec3 ambient = sceneAmbient(options.scene);
  const glm::mat4 view =
      glm::lookAtRH(glm::vec3(0.9f, 0.8f, 2.2f), glm::vec3(0.0f, 0.55f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
  const glm::vec3 eye = glm::vec3(glm::inverse(view)[3]);
  const glm::vec4 box(0.35f, 0.15f, 0.45f, 0.15f);  // centre, half size
  uint64_t jobsAfterFirstFrame = 0, waitsAfterFirstFrame = 0, waitsAtEnd = 0;
  HostTimes hostTimes;
  std::vector<std::pair<std::string, double>> times;
  bool written = false;
  {
    const std::unique_ptr<SmokeInstances> smoke = options.cApi ? cApiInstances(setup) : cppInstances(setup);

    // Each frame in flight draws into its own images; halfway through, the window grows.
    std::vector<std::unique_ptr<FrameImages>> images;
    auto makeImages = [&](uint32_t width, uint32_t height) {
      images.clear();
      for (uint32_t i = 0; i < kFramesInFlight; ++i)
        images.push_back(std::make_unique<FrameImages>(engine, width, height, kColorFormat, kDepthFormat));
    };
    makeImages(160, 120);
    const uint64_t frames = uint64_t(options.frames), resizeFrame = frames / 2;
    for (uint64_t frame = 0; frame < frames; ++frame) {
      if (frame == resizeFrame) {  // a resize: the engine waits for its frames and makes its targets anew
        loop.waitAll();
        makeImages(200, 150);
        smoke->forgetTargets();  // the old images are gone; the new ones may reuse their handles
      }
      const size_t slot = frame % kFramesInFlight;
      FrameImages& target = *images[slot];
      const FrameImagesView frameImages{target.color.image, target.color.view, target.depth.image,
                                        target.depth.view,  target.width,      target.height};
      VkCommandBuffer cmd = loop.begin(slot);
      changeLayout(cmd, target.color.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                   VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
      changeLayout(cmd, target.depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                   VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
      const glm::mat4 projection = jitteredProjection(frame, target.width, target.height);
      hostTimes.time("setCamera", frame, resizeFrame, [&] { smoke->setCamera(view, projection); });
      scenePass.record(cmd, target.color, target.depth, target.width, target.height,
                       {projection * view, box});

      // The engine's world: its emitter circles and is off through the middle third; a character (a capsule)
      // circles through the smoke, and a crate (a box) stands in it through the middle half.
      const float angle = 0.6f * float(frame);
      const EngineEmitter emitter{glm::vec3(0.1f * std::cos(angle), 0.1f, 0.1f * std::sin(angle)),
                                  0.15f,
                                  glm::vec3(0.0f, 1.5f, 0.0f),
                                  5.0f,
                                  5.0f,
                                  frame < frames / 3 || frame >= 2 * frames / 3};
      const double seconds = frameSeconds(frame);
      std::vector<EngineObstacle> obstacles = {
          {.shape = EngineObstacle::Shape::Capsule,
           .position = glm::vec3(0.12f, 0.62f, 0.1f) +
                       0.15f * glm::vec3(std::cos(angle) - 1.0f, 0.0f, std::sin(angle)),
           .radius = 0.07f,
           .height = 0.36f}};
      if (frame >= frames / 4 && frame < 3 * frames / 4)
        obstacles.push_back({.shape = EngineObstacle::Shape::Box,
                             .position = glm::vec3(-0.15f, 0.35f, -0.1f),
                             .size = glm::vec3(0.16f)});
      hostTimes.time("setEmitters+setObstacles", frame, resizeFrame,
                     [&] { smoke->setWorld(emitter, obstacles, seconds); });
      hostTimes.time("simulations' record", frame, resizeFrame,
                     [&] { smoke->recordSimulations(cmd, frame, seconds); });
      // B's lightmaps before the transparent pass, where its depth is read in the read-only layout.
      hostTimes.time("B recordLightmaps", frame, resizeFrame,
                     [&] { smoke->recordLightmapsB(cmd, frame, frameImages); });
      if (material)
        hostTimes.time("A lightmaps", frame, resizeFrame,
                       [&] { smoke->recordLightmapsA(cmd, frame, frameImages); });
      changeLayout(cmd, target.depth.image, VK_IMAGE_ASPECT_DEPTH_BIT,
                   VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL);
      // Far to near, by the distance to the middle of each instance's billboard.
      const bool bFirst = glm::distance(eye, smoke->middle(1)) > glm::distance(eye, smoke->middle(0));
      for (int instance : {bFirst ? 1 : 0, bFirst ? 0 : 1}) {
        if (instance == 1) {
          beginTransparentPass(cmd, target.color.view, target.depth.view, target.width, target.height);
          hostTimes.time("B recordComposite", frame, resizeFrame, [&] { smoke->recordCompositeB(cmd); });
          vkCmdEndRendering(cmd);
        } else {
          if (material) {
            beginTransparentPass(cmd, target.color.view, target.depth.view, target.width, target.height);
            material->draw(cmd, smoke->lightmapsA(), view, projection * view, setup.sunDirection,
                           setup.sunIrradiance, ambient, target.width, target.height);
            vkCmdEndRendering(cmd);
          } else {
            hostTimes.time("A record", frame, resizeFrame, [&] { smoke->recordA(cmd, frame, frameImages); });
          }
        }
      }
      changeLayout(cmd, target.color.image, VK_IMAGE_ASPECT_COLOR_BIT,
                   VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                   VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);  // ready to copy
      loop.submit(slot);
      if (frame != 0 && frame != resizeFrame) ++hostTimes.steadyFrames;
      if (frame == 0) {  // the first frame records sixway's passes and uploads what they need
        jobsAfterFirstFrame = loop.oneTimeJobs;
        waitsAfterFirstFrame = smoke->hostWaits();
      }
    }
    loop.waitAll();
    waitsAtEnd = smoke->hostWaits();
    written = writePng(engine, loop, *images[(frames - 1) % kFramesInFlight], options.out);
    times = smoke->stageTimes();
  }
  vkDestroyPipelineCache(engine.device, pipelineCache, nullptr);
  if (!written) throw std::runtime_error(options.out + ": cannot write the PNG");
  std::printf(
      "wrote %s: %d frames of 2 instances (%s API), %d validation messages, %llu host waits and %llu "
      "submissions by "
      "sixway "
      "after the first frame, %zu host allocations left\n",
      options.out.c_str(), options.frames, options.cApi ? "C" : "C++", validationMessages.load(),
      static_cast<unsigned long long>(waitsAtEnd - waitsAfterFirstFrame),
      static_cast<unsigned long long>(loop.oneTimeJobs - jobsAfterFirstFrame), allocator.live.size());
  for (const auto& [name, ms] : times) std::printf("  %-20s %8.2f ms\n", name.c_str(), ms);
  hostTimes.print();
  bool similar = true;
  if (!options.psnrAgainst.empty()) {
    const double decibels = psnr(options.out, options.psnrAgainst);
    similar = decibels >= options.minPsnr;
    std::printf("PSNR %.1f dB against %s (at least %.1f asked): %s\n", decibels, options.psnrAgainst.c_str(),
                options.minPsnr, similar ? "similar" : "too different");
  }
  return validationMessages.load() == 0 && allocator.live.empty() && similar ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse(argc, argv));
  } catch (const std::exception& e) {  // sixway::Error and the example's own: one line
    std::fprintf(stderr, "embed_vulkan: %s\n", e.what());
    return 1;
  }
}
