// The C API (include/sixway/sixway.h): what the C++ API throws arrives as a code and a one-line message per
// thread; nothing is thrown across it. A whole frame through it is tests/package's C consumer.
#include <gtest/gtest.h>
#include <sixway/device.h>
#include <sixway/sixway.h>

#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/device_features.h"
#include "runtime/engine_harness.h"
#include "runtime/internal.h"

namespace {

const std::filesystem::path kScene = std::filesystem::path(SIXWAY_TEST_DATA_DIR) / "scenes/small_plume.json";
const std::filesystem::path kWeights = std::filesystem::path(SIXWAY_TEST_DATA_DIR) / "nn/tiny.safetensors";

TEST(CApi, NullHandlesAreInvalidArgumentsNamingTheCall) {
  EXPECT_EQ(sixwayCreateOwnDevice(0, nullptr), SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(std::string(sixwayLastError()), "sixwayCreateOwnDevice: device is null");
  EXPECT_EQ(sixwaySimulationAdvance(nullptr), SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(std::string(sixwayLastError()), "sixwaySimulationAdvance: simulation is null");
  EXPECT_EQ(sixwaySimulationRecordSeconds(nullptr, VK_NULL_HANDLE, 0, 0.1, nullptr),
            SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(std::string(sixwayLastError()), "sixwaySimulationRecordSeconds: simulation is null");
  EXPECT_EQ(sixwaySimulationSetPlacement(nullptr, nullptr), SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(std::string(sixwayLastError()), "sixwaySimulationSetPlacement: simulation is null");
  const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  EXPECT_EQ(sixwayRendererSetViewProjection(nullptr, identity, identity), SIXWAY_ERROR_INVALID_ARGUMENT);
  sixwayDestroyRenderer(nullptr);  // no-ops, as free(NULL)
  sixwayDestroySimulation(nullptr);
  sixwayDestroyDevice(nullptr);
}

TEST(CApi, ErrorsAndMisuseComeBackAsCodesWithTheirMessages) {
  SixwayDevice device = nullptr;
  ASSERT_EQ(sixwayCreateOwnDevice(1, &device), SIXWAY_SUCCESS) << sixwayLastError();
  SixwaySimulation simulation = nullptr;
  EXPECT_EQ(sixwayCreateSimulation(device, "no/such/scene.json", &simulation), SIXWAY_ERROR);
  EXPECT_EQ(simulation, nullptr);
  EXPECT_NE(std::string(sixwayLastError()).find("no/such/scene.json"), std::string::npos)
      << sixwayLastError();

  SixwaySmokeDomain domain;
  sixwaySmokeDomainDefaults(&domain);
  EXPECT_EQ(domain.cells[1], 48);
  domain.lightmapSize = 40;
  EXPECT_EQ(sixwayCreateSimulationFromDomain(device, &domain, &simulation), SIXWAY_ERROR);
  EXPECT_NE(std::string(sixwayLastError()).find("render.lightmap_size"), std::string::npos)
      << sixwayLastError();
  domain.lightmapSize = 32;
  ASSERT_EQ(sixwayCreateSimulationFromDomain(device, &domain, &simulation), SIXWAY_SUCCESS)
      << sixwayLastError();
  sixwayDestroySimulation(simulation);

  ASSERT_EQ(sixwayCreateSimulation(device, kScene.c_str(), &simulation), SIXWAY_SUCCESS) << sixwayLastError();
  SixwayRenderer renderer = nullptr;
  EXPECT_EQ(sixwayCreateRenderer(device, simulation, "no/such/weights.safetensors", nullptr, &renderer),
            SIXWAY_ERROR);
  EXPECT_NE(std::string(sixwayLastError()).find("no/such/weights.safetensors"), std::string::npos);
  ASSERT_EQ(sixwayCreateRenderer(device, simulation, kWeights.c_str(), nullptr, &renderer), SIXWAY_SUCCESS)
      << sixwayLastError();

  // An own-image renderer records nothing into an engine's command buffer: std::invalid_argument in C++.
  EXPECT_EQ(sixwayRendererRecord(renderer, VK_NULL_HANDLE, 0), SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(sixwayLastError()).find("needs an engine target"), std::string::npos);
  // An orthographic projection is refused.
  const float view[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -3, 1};
  const float ortho[16] = {1, 0, 0, 0, 0, -1, 0, 0, 0, 0, -0.1f, 0, 0, 0, 0.5f, 1};
  EXPECT_EQ(sixwayRendererSetViewProjection(renderer, view, ortho), SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(sixwayLastError()).find("not a perspective"), std::string::npos) << sixwayLastError();

  const float doubled[16] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1};
  EXPECT_EQ(sixwaySimulationSetPlacement(simulation, doubled), SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(sixwayLastError()).find("no tilt, scale or mirror"), std::string::npos)
      << sixwayLastError();
  const float moved[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 4, 0, 0, 1};
  EXPECT_EQ(sixwaySimulationSetPlacement(simulation, moved), SIXWAY_SUCCESS);
  const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  EXPECT_EQ(sixwaySimulationSetPlacement(simulation, identity), SIXWAY_SUCCESS);

  SixwayEmitter emitter = {{0.0f, 0.2f, 0.0f}, 0.1f, {0.0f, 100.0f, 0.0f}, 1.0f, 0.0f, 1};
  EXPECT_EQ(sixwaySimulationSetEmitters(simulation, nullptr, 1), SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sixwaySimulationSetEmitters(simulation, &emitter, 1), SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(sixwayLastError()).find("emitter 0: speed 100"), std::string::npos)
      << sixwayLastError();
  emitter.velocity[1] = 0.5f;
  EXPECT_EQ(sixwaySimulationSetEmitters(simulation, &emitter, 1), SIXWAY_SUCCESS) << sixwayLastError();
  SixwayLight light = {5, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, 3.0f, 1};
  EXPECT_EQ(sixwayRendererSetLights(renderer, &light, 1), SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(sixwayLastError()).find("kind 5"), std::string::npos) << sixwayLastError();
  light.kind = 0;
  EXPECT_EQ(sixwayRendererSetLights(renderer, &light, 1), SIXWAY_SUCCESS) << sixwayLastError();
  EXPECT_EQ(sixwayRendererSetLights(renderer, nullptr, 1), SIXWAY_ERROR_INVALID_ARGUMENT);
  const float target[3] = {0.1f, 0.7f, 0.1f};
  EXPECT_EQ(sixwaySimulationSteerObstacle(simulation, 3, target, 0.1), SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sixwaySimulationSteerObstacle(simulation, 0, target, 0.1), SIXWAY_SUCCESS) << sixwayLastError();
  SixwayObstacle obstacles[2] = {{SIXWAY_OBSTACLE_CAPSULE, {0.1f, 0.7f, 0.1f}, 0.1f, {}, 0.1f, {0, 1, 0}, 1},
                                 {SixwayObstacleShape(7), {0.0f, 0.5f, 0.0f}, 0.1f, {}, 0.0f, {}, 1}};
  EXPECT_EQ(sixwaySimulationSetObstacles(simulation, nullptr, 1, 0.1), SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sixwaySimulationSetObstacles(simulation, obstacles, 1, 0.1), SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(sixwayLastError()).find("obstacle 0: a capsule's height 0.1"), std::string::npos)
      << sixwayLastError();
  obstacles[0].height = 0.4f;
  EXPECT_EQ(sixwaySimulationSetObstacles(simulation, obstacles, 2, 0.1), SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(sixwayLastError()).find("obstacle 1 has no shape 7"), std::string::npos)
      << sixwayLastError();
  EXPECT_EQ(sixwaySimulationSetObstacles(simulation, obstacles, 1, 0.1), SIXWAY_SUCCESS) << sixwayLastError();
  uint32_t obstacleCount = 0;
  EXPECT_EQ(sixwaySimulationObstacleCount(simulation, &obstacleCount), SIXWAY_SUCCESS);
  EXPECT_EQ(obstacleCount, 1u);

  ASSERT_EQ(sixwaySimulationAdvance(simulation), SIXWAY_SUCCESS);
  ASSERT_EQ(sixwayRendererRender(renderer), SIXWAY_SUCCESS);
  uint32_t width = 0, height = 0;
  ASSERT_EQ(sixwayRendererSize(renderer, &width, &height), SIXWAY_SUCCESS);
  std::vector<float> pixels(size_t(width) * height * 4);
  EXPECT_EQ(sixwayRendererImage(renderer, pixels.data(), pixels.size() - 1), SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sixwayRendererImage(renderer, pixels.data(), pixels.size()), SIXWAY_SUCCESS);

  // The message is the calling thread's: a failure elsewhere leaves it.
  const std::string mine = sixwayLastError();
  std::thread([] { sixwaySimulationAdvance(nullptr); }).join();
  EXPECT_EQ(std::string(sixwayLastError()), mine);

  sixwayDestroyRenderer(renderer);
  sixwayDestroySimulation(simulation);
  sixwayDestroyDevice(device);
}

// The engine's upload path through C: its callback records sixway's one-time work into a command buffer of
// its own, submits and waits.
void submitAndWait(void* user, void (*record)(void*, VkCommandBuffer), void* recordContext) {
  auto* uploads = static_cast<sixway::test::EngineUploads*>(user);
  ++uploads->calls;
  record(recordContext, uploads->commands.begin());
  uploads->commands.submitAndWait();
}

TEST(CApi, AnEngineDeviceTakesTheEnginesSubmitCallback) {
  sixway::Device own({.validate = true});
  const sixway::gpu::Context& context = sixway::runtime::Access::context(own);
  sixway::test::EngineUploads uploads(context);
  sixway::gpu::DeviceFeatures features = sixway::gpu::DeviceFeatures::toEnable(
      sixway::gpu::DeviceFeatures::supportedBy(context.physicalDevice()));
  const std::vector<const char*> extensions = sixway::gpu::requiredDeviceExtensions();
  SixwayEngineDevice engine{context.instance(),
                            context.physicalDevice(),
                            context.device(),
                            context.queue(),
                            context.queueFamily(),
                            extensions.data(),
                            uint32_t(extensions.size()),
                            features.chain(),
                            2,
                            submitAndWait,
                            &uploads};
  SixwayDevice device = nullptr;
  ASSERT_EQ(sixwayCreateEngineDevice(&engine, &device), SIXWAY_SUCCESS) << sixwayLastError();
  SixwaySimulation simulation = nullptr;
  ASSERT_EQ(sixwayCreateSimulation(device, kScene.c_str(), &simulation), SIXWAY_SUCCESS) << sixwayLastError();
  EXPECT_GT(uploads.calls, 0) << "the simulation's uploads did not go through the engine";
  sixwayDestroySimulation(simulation);
  sixwayDestroyDevice(device);
  EXPECT_EQ(own.validationMessages(), 0u);
}

}  // namespace
