#include "gpu/context.h"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "gpu/address_space.h"
#include "gpu/check.h"
#include "gpu/device_features.h"
#include "gpu/vulkan_functions.h"

namespace sixway::gpu {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* user) {
  static_cast<ValidationLog*>(user)->add(data->pMessage);
  return VK_FALSE;
}

VkDebugUtilsMessengerCreateInfoEXT messengerInfo(ValidationLog* log) {
  VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  info.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType =
      VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
  info.pfnUserCallback = onValidationMessage;
  info.pUserData = log;
  return info;
}

bool hasLayer(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  return std::any_of(layers.begin(), layers.end(),
                     [&](auto& l) { return std::strcmp(l.layerName, name) == 0; });
}

std::optional<uint32_t> computeGraphicsFamily(VkPhysicalDevice device) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  for (uint32_t i = 0; i < count; ++i) {
    const VkQueueFlags needed = VK_QUEUE_COMPUTE_BIT | VK_QUEUE_GRAPHICS_BIT;
    if ((families[i].queueFlags & needed) == needed) return i;
  }
  return std::nullopt;
}

// Why a device cannot run sixway, or empty when it can.
std::string unsuitability(VkPhysicalDevice device) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(device, &props);
  if (props.apiVersion < VK_API_VERSION_1_3) return "needs Vulkan 1.3";
  if (!computeGraphicsFamily(device)) return "has no queue with both compute and graphics";
  if (!hasDeviceExtension(device, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME))
    return "lacks VK_KHR_push_descriptor";
  return {};
}

int typeRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 1;
    default:
      return 0;
  }
}

std::optional<int> deviceIndexFromEnvironment() {
  const char* value = std::getenv("SIXWAY_DEVICE");
  if (!value || !*value) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const long index = std::strtol(value, &end, 10);
  // Out of long's range strtol saturates (ERANGE), and past int's the cast wrapped to "--device -1".
  if (end == value || *end != '\0' || index < 0 || errno == ERANGE || index > INT_MAX)
    throw GpuError(std::string("SIXWAY_DEVICE: expected a device index, got '") + value + "'");
  return static_cast<int>(index);
}

// The device index asked for and where it was asked: "--device N" or "SIXWAY_DEVICE=N", so that an error
// names what the user set.
struct RequestedDevice {
  int index;
  std::string source;
};

std::optional<RequestedDevice> requestedDevice(const ContextOptions& options) {
  if (options.deviceIndex)
    return RequestedDevice{*options.deviceIndex, "--device " + std::to_string(*options.deviceIndex)};
  if (const std::optional<int> index = deviceIndexFromEnvironment())
    return RequestedDevice{*index, "SIXWAY_DEVICE=" + std::to_string(*index)};
  return std::nullopt;
}

void checkDeviceIndex(const RequestedDevice& requested, uint32_t count) {
  if (requested.index < 0 || requested.index >= static_cast<int>(count))
    throw GpuError(requested.source + ": no such device; valid indices are 0.." + std::to_string(count - 1) +
                   " (see `sixway info`)");
}

}  // namespace

void checkRequestedDevice(const ContextOptions& options) {
  const std::optional<RequestedDevice> requested = requestedDevice(options);
  if (!requested) return;
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.apiVersion = VK_API_VERSION_1_3;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  VkInstance instance = VK_NULL_HANDLE;
  const VkResult result = vkCreateInstance(&info, nullptr, &instance);
  if (result != VK_SUCCESS) return;  // the Context says why it cannot start
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  vkDestroyInstance(instance, nullptr);
  if (count > 0) checkDeviceIndex(*requested, count);
}

void ValidationLog::add(const char* message) {
  std::fprintf(stderr, "validation: %s\n", message);
  std::lock_guard lock(mutex_);
  messages_.emplace_back(message);
  ++count_;
}

std::vector<std::string> ValidationLog::messages() const {
  std::lock_guard lock(mutex_);
  return messages_;
}

void ValidationLog::clear() {
  std::lock_guard lock(mutex_);
  messages_.clear();
  count_ = 0;
}

Context::Context(const ContextOptions& options) {
  createInstance(options);
  try {
    pickPhysicalDevice(options);
    createDevice(options);
    requireAddressSpaceHeadroom();
  } catch (...) {
    release();
    throw;
  }
}

MemoryBlock Context::allocateMemory(const VkMemoryRequirements& requirements, uint32_t type, bool map,
                                    const std::string& what) const {
  const auto exhausted = [&] {
    return LimitError(what + ": out of device memory allocating " + formatBytes(requirements.size));
  };
  if (memoryAllocator_.allocate) {
    const MemoryBlock block = memoryAllocator_.allocate(requirements, type, map);
    if (!block.memory) throw exhausted();
    if (block.offset % requirements.alignment != 0 || (map && !block.mapped)) {
      memoryAllocator_.free(block);
      throw GpuError(what + ": the engine's allocator gave a block " +
                     (map && !block.mapped ? "without its mapping" : "off the required alignment"));
    }
    return block;
  }
  VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  info.allocationSize = requirements.size;
  info.memoryTypeIndex = type;
  MemoryBlock block;
  const VkResult result = vkAllocateMemory(device_, &info, allocator_, &block.memory);
  if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY) throw exhausted();
  SIXWAY_VK(result);
  if (map) {
    const VkResult mapped = vkMapMemory(device_, block.memory, 0, VK_WHOLE_SIZE, 0, &block.mapped);
    if (mapped != VK_SUCCESS) {
      vkFreeMemory(device_, block.memory, allocator_);
      SIXWAY_VK(mapped);
    }
  }
  return block;
}

void Context::freeMemory(const MemoryBlock& block) const {
  if (!block.memory) return;
  if (memoryAllocator_.free)
    memoryAllocator_.free(block);
  else
    vkFreeMemory(device_, block.memory, allocator_);
}

void Context::note(const std::string& line) const {
  if (log_)
    log_(line);
  else
    std::fprintf(stderr, "sixway: note: %s\n", line.c_str());
}

Context::Context(const ExternalDevice& external)
    : instance_(external.instance),
      physicalDevice_(external.physicalDevice),
      device_(external.device),
      queue_(external.queue),
      queueFamily_(external.queueFamily),
      ownsDevice_(false),
      framesInFlight_(external.framesInFlight),
      externalSubmit_(external.submitAndWait),
      allocator_(external.allocator),
      externalPipelineCache_(external.pipelineCache),
      log_(external.log),
      memoryAllocator_(external.memory) {
  if (external.getInstanceProcAddr)
    engineFunctions_ = std::make_unique<EngineVulkanFunctions>(external.getInstanceProcAddr, instance_);
  if (bool(memoryAllocator_.allocate) != bool(memoryAllocator_.free))
    throw GpuError("external device: a memory allocator needs both its allocate and its free function");
  if (!instance_ || !physicalDevice_ || !device_ || !queue_)
    throw GpuError("external device: instance, physical device, device and queue must all be given");
  if (framesInFlight_ < 1 || framesInFlight_ > 8)
    throw GpuError("external device: framesInFlight must be in [1, 8] (got " +
                   std::to_string(framesInFlight_) + ")");
  readProperties();
  const std::string name = properties_.deviceName;
  if (properties_.apiVersion < VK_API_VERSION_1_3)
    throw GpuError("external device " + name + ": needs Vulkan 1.3");
  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, families.data());
  const VkQueueFlags needed = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  if (queueFamily_ >= familyCount || (families[queueFamily_].queueFlags & needed) != needed)
    throw GpuError("external device " + name + ": queue family " + std::to_string(queueFamily_) +
                   " does not do both graphics and compute");
  for (const char* extension : requiredDeviceExtensions())
    if (std::find(external.enabledExtensions.begin(), external.enabledExtensions.end(), extension) ==
        external.enabledExtensions.end())
      throw GpuError("external device " + name + ": extension " + extension +
                     " is not enabled (see sixway::DeviceRequirements)");
  const DeviceFeatures enabled = DeviceFeatures::fromChain(external.enabledFeatures);
  if (const auto missing = enabled.missingRequired(); !missing.empty())
    throw GpuError("external device " + name + ": feature " + missing.front() +
                   " is not enabled (see sixway::DeviceRequirements)");
  capabilities_.shaderFloat16 = enabled.vulkan12().shaderFloat16;
  capabilities_.storage16Bit = enabled.vulkan11().storageBuffer16BitAccess;
  capabilities_.independentBlend = enabled.core().independentBlend;
  if (chainEnablesCooperativeMatrix(external.enabledExtensions, external.enabledFeatures))
    capabilities_.cooperativeMatrix =
        offeredMatrixShape(instance_, physicalDevice_,
                           {capabilities_.subgroupSize, capabilities_.shaderFloat16,
                            capabilities_.storage16Bit, bool(enabled.vulkan12().vulkanMemoryModel)});
  cmdPushDescriptorSet = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
      vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));
}

Context::~Context() {
  release();
}

void Context::release() {
  if (!ownsDevice_) return;
  if (device_) vkDestroyDevice(device_, nullptr);
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
  device_ = VK_NULL_HANDLE;
  messenger_ = VK_NULL_HANDLE;
  instance_ = VK_NULL_HANDLE;
}

void Context::createInstance(const ContextOptions& options) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "sixway";
  app.pEngineName = "sixway";
  app.apiVersion = VK_API_VERSION_1_3;

  std::vector<const char*> extensions;
  for (auto& e : options.instanceExtensions) extensions.push_back(e.c_str());
  std::vector<const char*> layers;
  VkDebugUtilsMessengerCreateInfoEXT debugInfo{};
  if (options.validate) {
    if (!hasLayer(kValidationLayer))
      throw GpuError(
          "--validate: the Vulkan validation layer is not installed (Debian: vulkan-validationlayers)");
    validation_ = std::make_unique<ValidationLog>();
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    debugInfo = messengerInfo(validation_.get());
  }

  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pNext = options.validate ? &debugInfo : nullptr;  // also reports instance creation itself
  info.pApplicationInfo = &app;
  info.enabledLayerCount = static_cast<uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  VkResult result = vkCreateInstance(&info, nullptr, &instance_);
  if (result == VK_ERROR_INCOMPATIBLE_DRIVER)
    throw GpuError("no Vulkan driver found (install mesa-vulkan-drivers for the lavapipe CPU device)");
  SIXWAY_VK(result);

  if (options.validate) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    SIXWAY_VK(create(instance_, &debugInfo, nullptr, &messenger_));
  }
}

void Context::pickPhysicalDevice(const ContextOptions& options) {
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance_, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance_, &count, devices.data());
  if (devices.empty()) throw GpuError("no Vulkan device found (install mesa-vulkan-drivers for lavapipe)");

  if (const std::optional<RequestedDevice> requested = requestedDevice(options)) {
    checkDeviceIndex(*requested, count);
    physicalDevice_ = devices[requested->index];
    if (std::string why = unsuitability(physicalDevice_); !why.empty())
      throw GpuError(requested->source + ": the device " + why);
  } else {
    int bestRank = -1;
    for (VkPhysicalDevice device : devices) {
      if (!unsuitability(device).empty()) continue;
      VkPhysicalDeviceProperties props;
      vkGetPhysicalDeviceProperties(device, &props);
      if (typeRank(props.deviceType) > bestRank) {
        bestRank = typeRank(props.deviceType);
        physicalDevice_ = device;
      }
    }
    if (!physicalDevice_)
      throw GpuError("no Vulkan device has what sixway needs (" + unsuitability(devices[0]) + ")");
  }
  queueFamily_ = *computeGraphicsFamily(physicalDevice_);
  readProperties();
}

void Context::readProperties() {
  driver_ = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES,
                                              &driver_};
  VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &subgroup};
  vkGetPhysicalDeviceProperties2(physicalDevice_, &props2);
  properties_ = props2.properties;
  vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memory_);

  capabilities_.subgroupSize = subgroup.subgroupSize;
  capabilities_.timestampPeriodNs = properties_.limits.timestampPeriod;
  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, families.data());
  capabilities_.timestampValidBits = families[queueFamily_].timestampValidBits;
  capabilities_.timestamps =
      properties_.limits.timestampComputeAndGraphics && capabilities_.timestampValidBits > 0;
  for (uint32_t i = 0; i < memory_.memoryHeapCount; ++i)
    if (memory_.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
      capabilities_.deviceLocalHeapBytes =
          std::max<uint64_t>(capabilities_.deviceLocalHeapBytes, memory_.memoryHeaps[i].size);
}

void Context::createDevice(const ContextOptions& options) {
  const DeviceFeatures supported = DeviceFeatures::supportedBy(physicalDevice_);
  if (const auto missing = supported.missingRequired(); !missing.empty())
    throw GpuError(std::string(properties_.deviceName) + ": needs " + missing.front());
  // Enable what the stages use; the optional 16-bit paths only where the device has them.
  DeviceFeatures enable = DeviceFeatures::toEnable(supported);
  capabilities_.shaderFloat16 = enable.vulkan12().shaderFloat16;
  capabilities_.storage16Bit = enable.vulkan11().storageBuffer16BitAccess;
  capabilities_.independentBlend = enable.core().independentBlend;

  std::vector<const char*> extensions = requiredDeviceExtensions();
  if (options.presentation) extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  // Cooperative matrices where the device offers a shape the network's conv2d can use.
  VkPhysicalDeviceCooperativeMatrixFeaturesNV matrixFeatures{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_COOPERATIVE_MATRIX_FEATURES_NV};
  capabilities_.cooperativeMatrix =
      offeredMatrixShape(instance_, physicalDevice_,
                         {capabilities_.subgroupSize, capabilities_.shaderFloat16, capabilities_.storage16Bit,
                          bool(enable.vulkan12().vulkanMemoryModel)});
  if (capabilities_.cooperativeMatrix) {
    extensions.push_back(VK_NV_COOPERATIVE_MATRIX_EXTENSION_NAME);
    matrixFeatures.cooperativeMatrix = VK_TRUE;
    matrixFeatures.pNext = enable.chain()->pNext;
    enable.chain()->pNext = &matrixFeatures;
  }

  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = queueFamily_;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;

  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, enable.chain()};
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queueInfo;
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  SIXWAY_VK(vkCreateDevice(physicalDevice_, &info, nullptr, &device_));
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
  cmdPushDescriptorSet = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
      vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));
}

uint32_t Context::findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required) const {
  for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
    if ((typeBits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & required) == required) return i;
  throw GpuError("no memory type with the required properties on " + std::string(properties_.deviceName));
}

void Context::requireStorageBufferFits(uint64_t bytes, const std::string& what) const {
  const uint64_t range = properties_.limits.maxStorageBufferRange;
  if (bytes > range)
    throw LimitError(what + " needs a storage buffer of " + formatBytes(bytes) + ", more than the " +
                     formatBytes(range) + " that " + properties_.deviceName + " can bind");
  if (bytes > capabilities_.deviceLocalHeapBytes)
    throw LimitError(what + " needs " + formatBytes(bytes) + ", more than the device's " +
                     formatBytes(capabilities_.deviceLocalHeapBytes) + " of memory");
}

std::vector<std::string> listPhysicalDevices(VkInstance instance) {
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance, &count, devices.data());
  std::vector<std::string> lines;
  for (uint32_t i = 0; i < count; ++i) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(devices[i], &props);
    std::string line =
        std::to_string(i) + ": " + props.deviceName + " (" + deviceTypeName(props.deviceType) + ")";
    if (std::string why = unsuitability(devices[i]); !why.empty()) line += " — unusable: " + why;
    lines.push_back(line);
  }
  return lines;
}

const char* deviceTypeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "CPU";
    default:
      return "other";
  }
}

std::string formatBytes(uint64_t bytes) {
  std::ostringstream out;
  out.precision(3);
  if (bytes >= (1ull << 30))
    out << double(bytes) / double(1ull << 30) << " GiB";
  else if (bytes >= (1ull << 20))
    out << double(bytes) / double(1ull << 20) << " MiB";
  else if (bytes >= (1ull << 10))
    out << double(bytes) / double(1ull << 10) << " KiB";
  else
    out << bytes << " B";
  return out.str();
}

}  // namespace sixway::gpu
