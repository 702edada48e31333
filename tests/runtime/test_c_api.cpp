// The C API (include/sixway/sixway.h): what the C++ API throws arrives as a code and a one-line message per
// thread; nothing is thrown across it. A whole frame through it is tests/package's C consumer.
#include <gtest/gtest.h>
#include <sixway/sixway.h>

#include <filesystem>
#include <string>
#include <thread>
#include <vector>

namespace {

const std::filesystem::path kScene = std::filesystem::path(SIXWAY_TEST_DATA_DIR) / "scenes/small_plume.json";
const std::filesystem::path kWeights = std::filesystem::path(SIXWAY_TEST_DATA_DIR) / "nn/tiny.safetensors";

TEST(CApi, NullHandlesAreInvalidArgumentsNamingTheCall) {
  EXPECT_EQ(sixwayCreateOwnDevice(0, nullptr), SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(std::string(sixwayLastError()), "sixwayCreateOwnDevice: device is null");
  EXPECT_EQ(sixwaySimulationAdvance(nullptr), SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(std::string(sixwayLastError()), "sixwaySimulationAdvance: simulation is null");
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

}  // namespace
