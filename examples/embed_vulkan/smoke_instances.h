#pragma once
// The engine's two smoke instances behind the calls its frame loop makes, through sixway's C++ API
// (smoke_instances_cpp.cpp) or its C API (smoke_instances_c.cpp): the same frame either way. Instance A is
// drawn with per-frame targets (sixway moves the images to what it needs and back), or by the engine's own
// material from A's lightmaps in the RLT/BBF packing; instance B inside the engine's transparent pass; B runs
// A's network. Both are lit by the engine's sun.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>

// What the engine hands sixway at start.
struct SmokeSetup {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  std::vector<std::string> extensions;
  const void* features = nullptr;  // the chain given to vkCreateDevice
  uint32_t framesInFlight = 0;
  std::function<void(const std::function<void(VkCommandBuffer)>&)> submitAndWait;
  const VkAllocationCallbacks* allocator = nullptr;
  VkPipelineCache pipelineCache = VK_NULL_HANDLE;
  PFN_vkGetInstanceProcAddr getInstanceProcAddr = nullptr;  // the engine's loader (volk's, for one)
  std::string scene, weights;
  VkFormat colorFormat = VK_FORMAT_UNDEFINED, depthFormat = VK_FORMAT_UNDEFINED;
  glm::mat4 placementB{1.0f};  // where instance B stands in the world (A: where its scene puts it)
  bool ownMaterialA = false;   // A's lightmaps for the engine's material, not sixway's composite
  glm::vec3 sunDirection{0.0f, 1.0f, 0.0f}, sunIrradiance{3.14159265f};  // toward the sun; colour · intensity
};

// A's lightmaps this frame for the engine's material: RLT and BBF (sampled, GENERAL) and the world corners of
// their quad (bottom-left, bottom-right, top-right, top-left).
struct PackedLightmaps {
  VkImageView rlt = VK_NULL_HANDLE, bbf = VK_NULL_HANDLE;
  glm::vec3 corners[4];
};

// The engine's emitter in instance A this frame (sixway::Emitter's fields).
struct EngineEmitter {
  glm::vec3 position{0.0f};
  float radius = 0.0f;
  glm::vec3 velocity{0.0f};
  float densityRate = 0.0f, temperatureRate = 0.0f;
  bool on = true;
};

// An obstacle of the engine's world in instance A this frame (sixway::Obstacle's fields).
struct EngineObstacle {
  enum class Shape { Sphere, Box, Capsule } shape = Shape::Sphere;
  glm::vec3 position{0.0f};
  float radius = 0.0f;
  glm::vec3 size{0.0f};
  float height = 0.0f;
  glm::vec3 axis{0.0f, 1.0f, 0.0f};
};

// One frame's images: the colour in COLOR_ATTACHMENT_OPTIMAL and the depth in
// DEPTH_STENCIL_READ_ONLY_OPTIMAL while the smoke is drawn (and left so).
struct FrameImagesView {
  VkImage color = VK_NULL_HANDLE;
  VkImageView colorView = VK_NULL_HANDLE;
  VkImage depth = VK_NULL_HANDLE;
  VkImageView depthView = VK_NULL_HANDLE;
  uint32_t width = 0, height = 0;
};

class SmokeInstances {
 public:
  virtual ~SmokeInstances() = default;
  // Each frame, in this order: the camera of both; A's world (its emitter, its obstacles where they are
  // after `seconds`); both simulations; B's lightmaps before the transparent pass; then, far to near, A's
  // record and B's composite inside the transparent pass.
  virtual void setCamera(const glm::mat4& view, const glm::mat4& projection) = 0;
  virtual void setWorld(const EngineEmitter& emitter, const std::vector<EngineObstacle>& obstacles,
                        double seconds) = 0;
  virtual void recordSimulations(VkCommandBuffer commands, uint64_t frame, double seconds) = 0;
  virtual void recordLightmapsB(VkCommandBuffer commands, uint64_t frame, const FrameImagesView& images) = 0;
  virtual void recordA(VkCommandBuffer commands, uint64_t frame, const FrameImagesView& images) = 0;
  // With the engine's own material: A's lightmaps (before the transparent pass), then where they are.
  virtual void recordLightmapsA(VkCommandBuffer commands, uint64_t frame, const FrameImagesView& images) = 0;
  virtual PackedLightmaps lightmapsA() const = 0;
  virtual void recordCompositeB(VkCommandBuffer commands) = 0;
  // The engine destroyed the images it passed (a resize).
  virtual void forgetTargets() = 0;
  // The middle of instance 0's (A's) or 1's (B's) billboard after the last frame (before: its placement).
  virtual glm::vec3 middle(int instance) const = 0;
  virtual uint64_t hostWaits() const = 0;
  // GPU time per stage of A's simulation and both renderers (the C API has none).
  virtual std::vector<std::pair<std::string, double>> stageTimes() const = 0;
};

std::unique_ptr<SmokeInstances> cppInstances(const SmokeSetup& setup);
std::unique_ptr<SmokeInstances> cApiInstances(const SmokeSetup& setup);
