#include "gpu/context.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "gpu/check.h"

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

bool hasDeviceExtension(VkPhysicalDevice device, const char* name) {
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
  return std::any_of(extensions.begin(), extensions.end(),
                     [&](auto& e) { return std::strcmp(e.extensionName, name) == 0; });
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
  long index = std::strtol(value, &end, 10);
  if (*end != '\0' || index < 0)
    throw GpuError(std::string("SIXWAY_DEVICE: expected a device index, got '") + value + "'");
  return static_cast<int>(index);
}

}  // namespace

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
  pickPhysicalDevice(options);
  createDevice(options);
}

Context::~Context() {
  if (device_) vkDestroyDevice(device_, nullptr);
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
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

  std::optional<int> requested = options.deviceIndex ? options.deviceIndex : deviceIndexFromEnvironment();
  if (requested) {
    if (*requested < 0 || *requested >= static_cast<int>(count))
      throw GpuError("--device " + std::to_string(*requested) + ": no such device; valid indices are 0.." +
                     std::to_string(count - 1) + " (see `sixway info`)");
    physicalDevice_ = devices[*requested];
    if (std::string why = unsuitability(physicalDevice_); !why.empty())
      throw GpuError("--device " + std::to_string(*requested) + ": the device " + why);
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
  VkPhysicalDeviceShaderAtomicFloatFeaturesEXT supportedAtomics{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};
  VkPhysicalDeviceVulkan11Features supported11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES,
                                               &supportedAtomics};
  VkPhysicalDeviceVulkan12Features supported12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                                               &supported11};
  VkPhysicalDeviceVulkan13Features supported13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
                                               &supported12};
  VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &supported13};
  vkGetPhysicalDeviceFeatures2(physicalDevice_, &supported);
  if (!supported13.synchronization2 || !supported13.dynamicRendering || !supported13.maintenance4)
    throw GpuError(std::string(properties_.deviceName) +
                   ": needs synchronization2, dynamicRendering, maintenance4");

  // Enable what the stages use; the optional 16-bit paths only where the device has them.
  if (!supportedAtomics.shaderBufferFloat32AtomicAdd)
    throw GpuError(std::string(properties_.deviceName) + ": needs float atomic add on storage buffers");
  // Float atomic add: the simulation sums obstacle forces with it.
  VkPhysicalDeviceShaderAtomicFloatFeaturesEXT enableAtomics{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};
  enableAtomics.shaderBufferFloat32AtomicAdd = VK_TRUE;
  VkPhysicalDeviceVulkan11Features enable11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &enableAtomics};
  enable11.storageBuffer16BitAccess = supported11.storageBuffer16BitAccess;
  VkPhysicalDeviceVulkan12Features enable12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &enable11};
  enable12.shaderFloat16 = supported12.shaderFloat16;
  enable12.hostQueryReset = supported12.hostQueryReset;
  VkPhysicalDeviceVulkan13Features enable13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES, &enable12};
  enable13.synchronization2 = VK_TRUE;
  enable13.dynamicRendering = VK_TRUE;
  enable13.subgroupSizeControl = supported13.subgroupSizeControl;
  enable13.maintenance4 = VK_TRUE;  // workgroup sizes as specialization constants (LocalSizeId)
  VkPhysicalDeviceFeatures2 enable{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &enable13};
  enable.features.shaderInt64 = supported.features.shaderInt64;
  enable.features.fragmentStoresAndAtomics = supported.features.fragmentStoresAndAtomics;
  enable.features.shaderStorageImageWriteWithoutFormat =
      supported.features.shaderStorageImageWriteWithoutFormat;
  capabilities_.shaderFloat16 = supported12.shaderFloat16;
  capabilities_.storage16Bit = supported11.storageBuffer16BitAccess;

  std::vector<const char*> extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME,
                                         VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME};
  if (options.presentation) extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);

  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = queueFamily_;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;

  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &enable};
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
