// sixway on a device an engine owns: the external-device checks name what is missing, and a sequence
// recorded into the engine's command buffer takes each frame's parameters as they were when that frame was
// recorded, hands its results back a frame later, and never blocks the host.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/check.h"
#include "gpu/device_features.h"
#include "gpu/reduce_stats.h"
#include "gpu/sequence.h"
#include "support/gpu_fixture.h"

namespace sixway::test {
namespace {

std::vector<std::string> extensionNames(const std::vector<const char*>& names) {
  return {names.begin(), names.end()};
}

class EngineRecordingTest : public GpuTest {
 protected:
  // The fixture's device, described as an engine would describe its own, with three frames in flight.
  gpu::ExternalDevice engineDevice(gpu::DeviceFeatures& features) {
    const gpu::Context& c = context();
    features = gpu::DeviceFeatures::toEnable(gpu::DeviceFeatures::supportedBy(c.physicalDevice()));
    return {c.instance(),     c.physicalDevice(),
            c.device(),       c.queue(),
            c.queueFamily(),  extensionNames(gpu::requiredDeviceExtensions()),
            features.chain(), 3};
  }
};

TEST_F(EngineRecordingTest, AMissingFeatureOrExtensionIsNamed) {
  gpu::DeviceFeatures features;
  gpu::ExternalDevice device = engineDevice(features);
  gpu::DeviceFeatures withoutSync2 = features;
  const_cast<VkPhysicalDeviceVulkan13Features&>(withoutSync2.vulkan13()).synchronization2 = VK_FALSE;
  device.enabledFeatures = withoutSync2.chain();
  try {
    gpu::Context borrowed(device);
    FAIL() << "a device without synchronization2 was accepted";
  } catch (const gpu::GpuError& e) {
    EXPECT_NE(std::string(e.what()).find("feature synchronization2 is not enabled"), std::string::npos)
        << e.what();
  }
  device = engineDevice(features);
  device.enabledExtensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
  try {
    gpu::Context borrowed(device);
    FAIL() << "a device without float atomics was accepted";
  } catch (const gpu::GpuError& e) {
    EXPECT_NE(std::string(e.what()).find("extension VK_EXT_shader_atomic_float is not enabled"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(EngineRecordingTest, EachRecordedFrameSeesItsOwnParametersAndNothingWaits) {
  gpu::DeviceFeatures features;
  const gpu::Context borrowed(engineDevice(features));
  gpu::PipelineCache cache(borrowed);
  constexpr uint32_t kCount = 1000;
  gpu::Buffer values(borrowed, kCount * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                     gpu::MemoryKind::FrameParameters, "values");
  gpu::ReduceStats stats(borrowed, cache, kCount);
  gpu::Sequence sequence(borrowed);
  stats.record(sequence, values, kCount);
  sequence.addReadback(stats.resultBuffer());
  sequence.finish();

  // The engine's command buffer: three frames recorded before any of them runs.
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.queueFamilyIndex = borrowed.queueFamily();
  VkCommandPool pool;
  SIXWAY_VK(vkCreateCommandPool(borrowed.device(), &poolInfo, nullptr, &pool));
  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = pool;
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  VkCommandBuffer commands;
  SIXWAY_VK(vkAllocateCommandBuffers(borrowed.device(), &allocInfo, &commands));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  SIXWAY_VK(vkBeginCommandBuffer(commands, &begin));
  const uint64_t waitsBefore = borrowed.hostWaits();
  for (uint64_t frame = 0; frame < 3; ++frame) {
    std::vector<float> frameValues(kCount, float(frame + 1));
    std::memcpy(values.mapped(), frameValues.data(), kCount * sizeof(float));
    sequence.record(commands, frame);
  }
  EXPECT_EQ(borrowed.hostWaits(), waitsBefore) << "recording blocked the host";
  SIXWAY_VK(vkEndCommandBuffer(commands));

  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence;
  SIXWAY_VK(vkCreateFence(borrowed.device(), &fenceInfo, nullptr, &fence));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands;
  SIXWAY_VK(vkQueueSubmit(borrowed.queue(), 1, &submit, fence));
  SIXWAY_VK(vkWaitForFences(borrowed.device(), 1, &fence, VK_TRUE, UINT64_MAX));  // the engine's wait
  EXPECT_EQ(borrowed.hostWaits(), waitsBefore);

  for (uint64_t frame = 0; frame < 3; ++frame) {
    gpu::Stats result;
    std::memcpy(&result, sequence.readback(stats.resultBuffer(), frame).data(), sizeof(result));
    EXPECT_FLOAT_EQ(result.sum, float(kCount * (frame + 1))) << "frame " << frame;
    EXPECT_FLOAT_EQ(result.maximum, float(frame + 1)) << "frame " << frame;
    EXPECT_EQ(result.count, kCount);
  }
  vkDestroyFence(borrowed.device(), fence, nullptr);
  vkDestroyCommandPool(borrowed.device(), pool, nullptr);
}

}  // namespace
}  // namespace sixway::test
