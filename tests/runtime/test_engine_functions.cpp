// The engine's Vulkan functions (EngineDevice::getInstanceProcAddr): an engine's vkGetInstanceProcAddr — here
// a layer of its own in front of the loader that counts what sixway asks for and the dispatches it records —
// serves every Vulkan call sixway makes while the engine's device lives, with the same image as the loader's;
// afterwards sixway calls the loader again. One it cannot serve is an Error naming the function.
#include <gtest/gtest.h>
#include <sixway/device.h>
#include <sixway/errors.h>
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>

#include <cstring>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "gpu/device_features.h"
#include "gpu/vulkan_functions.h"
#include "runtime/engine_harness.h"
#include "support/temp_dir.h"

namespace sixway::test {
namespace {

// The engine's layer: what sixway asked it for, and the dispatches recorded through it.
std::set<std::string> asked;
uint64_t dispatches = 0;

VKAPI_ATTR void VKAPI_CALL countingCmdDispatch(VkCommandBuffer commands, uint32_t x, uint32_t y, uint32_t z) {
  ++dispatches;
  ::vkCmdDispatch(commands, x, y, z);
}

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL countingGetInstanceProcAddr(VkInstance instance, const char* name) {
  asked.insert(name);
  if (std::strcmp(name, "vkCmdDispatch") == 0)
    return reinterpret_cast<PFN_vkVoidFunction>(countingCmdDispatch);
  return ::vkGetInstanceProcAddr(instance, name);
}

// An engine whose loader lacks one function sixway calls.
VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL lackingGetInstanceProcAddr(VkInstance instance, const char* name) {
  if (std::strcmp(name, "vkCmdPipelineBarrier2") == 0) return nullptr;
  return ::vkGetInstanceProcAddr(instance, name);
}

Device deviceWithFunctions(BorrowingEngine& engine, PFN_vkGetInstanceProcAddr getInstanceProcAddr) {
  const std::vector<const char*> extensions = gpu::requiredDeviceExtensions();
  EngineDevice device{engine.context.instance(),    engine.context.physicalDevice(),
                      engine.context.device(),      engine.context.queue(),
                      engine.context.queueFamily(), {extensions.begin(), extensions.end()},
                      engine.features.chain(),      2};
  device.getInstanceProcAddr = getInstanceProcAddr;
  return Device(device);
}

std::vector<float> smokeImage(BorrowingEngine& engine, Device& device, const std::filesystem::path& scene) {
  const float background[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  EngineTargets targets(engine.context, 64, 64);
  SmokeSimulation simulation(device, scene);
  SmokeRenderer renderer(device, simulation, {.weights = kWeights}, targets.target());
  renderer.setCamera(sceneCamera());
  recordFrames(engine, targets, simulation, renderer, background);
  return targets.colorPixels();
}

TEST(EngineFunctions, EveryVulkanCallGoesThroughTheEnginesGetInstanceProcAddr) {
  TempDir dir;
  const std::filesystem::path scene = sceneWithoutObstacles(dir.path());
  Device own({.validate = true});
  BorrowingEngine engine(own);
  const std::vector<float> expected = smokeImage(engine, engine.device, scene);
  asked.clear();
  dispatches = 0;
  {
    Device device = deviceWithFunctions(engine, countingGetInstanceProcAddr);
    EXPECT_EQ(maxDifference(smokeImage(engine, device, scene), expected), 0.0);
    EXPECT_GT(dispatches, 0u) << "the dispatches did not go through the engine's functions";
  }
  for (const char* name : {"vkCreateInstance", "vkCmdDispatch", "vkCmdPipelineBarrier2", "vkCreateBuffer",
                           "vkCreateComputePipelines", "vkCmdExecuteCommands", "vkGetDeviceProcAddr"})
    EXPECT_EQ(asked.count(name), 1u) << name << " was not asked of the engine";
  const uint64_t dispatchesWhileHeld = dispatches;
  EXPECT_EQ(maxDifference(smokeImage(engine, engine.device, scene), expected), 0.0);
  EXPECT_EQ(dispatches, dispatchesWhileHeld) << "the engine's functions were still called after its device";
  EXPECT_EQ(own.validationMessages(), 0u);
}

TEST(EngineFunctions, AFunctionTheEngineLacksOrASecondLoaderIsAnErrorNamingIt) {
  Device own({.validate = true});
  BorrowingEngine engine(own);
  try {
    Device device = deviceWithFunctions(engine, lackingGetInstanceProcAddr);
    ADD_FAILURE() << "a device without vkCmdPipelineBarrier2 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("gives no vkCmdPipelineBarrier2"), std::string::npos) << e.what();
  }
  EXPECT_EQ(gpu::vkCmdPipelineBarrier2, &::vkCmdPipelineBarrier2) << "a refused engine left its functions";
  {
    Device first = deviceWithFunctions(engine, countingGetInstanceProcAddr);
    Device same = deviceWithFunctions(engine, countingGetInstanceProcAddr);
    try {
      Device other = deviceWithFunctions(engine, lackingGetInstanceProcAddr);
      ADD_FAILURE() << "a second engine loader was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("one per process"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(gpu::vkCmdDispatch, &::vkCmdDispatch) << "the loader's functions are not back";
  EXPECT_EQ(own.validationMessages(), 0u);
}

}  // namespace
}  // namespace sixway::test
