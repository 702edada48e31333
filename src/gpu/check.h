#pragma once
// Vulkan call checking: a failed call becomes a GpuError that names the call and the VkResult.
#include <vulkan/vulkan.h>

#include <sixway/errors.h>
#include <string>

namespace sixway::gpu {

// Any failure of the device or the driver (as opposed to bad user input, see io::InputError).
class GpuError : public Error {
 public:
  using Error::Error;
};

// A buffer or image that the device cannot hold or bind, refused before allocation. what() ends in
// "; reduce its size"; problem() is the message without it, for callers that can name the setting to reduce
// (the command line: the scene's grid.size, --voxels, ...).
class LimitError : public GpuError {
 public:
  explicit LimitError(const std::string& problem)
      : GpuError(problem + "; reduce its size"), problem_(problem) {}
  const std::string& problem() const { return problem_; }

 private:
  std::string problem_;
};

const char* resultName(VkResult result);
void throwOnFailure(VkResult result, const char* call);

}  // namespace sixway::gpu

#define SIXWAY_VK(call) ::sixway::gpu::throwOnFailure((call), #call)
