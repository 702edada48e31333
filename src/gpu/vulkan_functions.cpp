// The defaults are the linked loader's own entry points, so this file alone sees Vulkan's prototypes.
#undef VK_NO_PROTOTYPES
#include "gpu/vulkan_functions.h"

#include <mutex>
#include <string>

#include "gpu/check.h"

namespace sixway::gpu {

#define SIXWAY_DEFINE_VULKAN_FUNCTION(name) PFN_##name name = ::name;
SIXWAY_VULKAN_GLOBAL_FUNCTIONS(SIXWAY_DEFINE_VULKAN_FUNCTION)
SIXWAY_VULKAN_FUNCTIONS(SIXWAY_DEFINE_VULKAN_FUNCTION)
SIXWAY_DEFINE_VULKAN_FUNCTION(vkGetInstanceProcAddr)
#undef SIXWAY_DEFINE_VULKAN_FUNCTION

namespace {

std::mutex holdersMutex;
int holders = 0;
PFN_vkGetInstanceProcAddr heldGetInstanceProcAddr = nullptr;

void useLoaderFunctions() {
#define SIXWAY_RESET_VULKAN_FUNCTION(name) name = ::name;
  SIXWAY_VULKAN_GLOBAL_FUNCTIONS(SIXWAY_RESET_VULKAN_FUNCTION)
  SIXWAY_VULKAN_FUNCTIONS(SIXWAY_RESET_VULKAN_FUNCTION)
  SIXWAY_RESET_VULKAN_FUNCTION(vkGetInstanceProcAddr)
#undef SIXWAY_RESET_VULKAN_FUNCTION
}

// Every function from `get`, or the name of the first it does not give (nothing changed then).
std::string useFunctionsOf(PFN_vkGetInstanceProcAddr get, VkInstance instance) {
  struct {
#define SIXWAY_FIELD(name) PFN_##name name = nullptr;
    SIXWAY_VULKAN_GLOBAL_FUNCTIONS(SIXWAY_FIELD)
    SIXWAY_VULKAN_FUNCTIONS(SIXWAY_FIELD)
#undef SIXWAY_FIELD
  } loaded;
#define SIXWAY_LOAD(name, from)                                 \
  loaded.name = reinterpret_cast<PFN_##name>(get(from, #name)); \
  if (!loaded.name) return #name;
#define SIXWAY_LOAD_GLOBAL(name) SIXWAY_LOAD(name, VK_NULL_HANDLE)
#define SIXWAY_LOAD_INSTANCE(name) SIXWAY_LOAD(name, instance)
  SIXWAY_VULKAN_GLOBAL_FUNCTIONS(SIXWAY_LOAD_GLOBAL)
  SIXWAY_VULKAN_FUNCTIONS(SIXWAY_LOAD_INSTANCE)
#undef SIXWAY_LOAD_INSTANCE
#undef SIXWAY_LOAD_GLOBAL
#undef SIXWAY_LOAD
#define SIXWAY_COPY(name) name = loaded.name;
  SIXWAY_VULKAN_GLOBAL_FUNCTIONS(SIXWAY_COPY)
  SIXWAY_VULKAN_FUNCTIONS(SIXWAY_COPY)
#undef SIXWAY_COPY
  vkGetInstanceProcAddr = get;
  return {};
}

}  // namespace

EngineVulkanFunctions::EngineVulkanFunctions(PFN_vkGetInstanceProcAddr getInstanceProcAddr,
                                             VkInstance instance) {
  std::lock_guard lock(holdersMutex);
  if (holders > 0 && getInstanceProcAddr != heldGetInstanceProcAddr)
    throw GpuError(
        "external device: its vkGetInstanceProcAddr differs from that of an engine device still in use "
        "(sixway's Vulkan functions come from one per process)");
  if (holders == 0) {
    if (const std::string missing = useFunctionsOf(getInstanceProcAddr, instance); !missing.empty())
      throw GpuError("external device: its vkGetInstanceProcAddr gives no " + missing);
    heldGetInstanceProcAddr = getInstanceProcAddr;
  }
  ++holders;
}

EngineVulkanFunctions::~EngineVulkanFunctions() {
  std::lock_guard lock(holdersMutex);
  if (--holders == 0) {
    heldGetInstanceProcAddr = nullptr;
    useLoaderFunctions();
  }
}

}  // namespace sixway::gpu
