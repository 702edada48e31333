#pragma once
// Vulkan call checking: a failed call becomes a GpuError that names the call and the VkResult.
#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>

namespace sixway::gpu {

// Any failure of the device or the driver (as opposed to bad user input, see io::InputError).
class GpuError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

const char* resultName(VkResult result);
void throwOnFailure(VkResult result, const char* call);

}  // namespace sixway::gpu

#define SIXWAY_VK(call) ::sixway::gpu::throwOnFailure((call), #call)
