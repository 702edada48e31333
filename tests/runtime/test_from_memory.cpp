// Scenes and weights from the engine's memory (SceneText, RendererOptions::weightsData, LightmapNetwork's
// bytes, the C API's FromText and RendererInfo): the same smoke, bit for bit, as from the files; errors name
// what the engine called them; files a scene names are found from the directory it gives.
#include <gtest/gtest.h>
#include <sixway/device.h>
#include <sixway/errors.h>
#include <sixway/lightmap_network.h>
#include <sixway/sixway.h>
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>

#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "runtime/engine_harness.h"

namespace sixway::test {
namespace {

std::string text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::vector<std::byte> bytes(const std::filesystem::path& file) {
  const std::string t = text(file);
  const auto* b = reinterpret_cast<const std::byte*>(t.data());
  return {b, b + t.size()};
}

std::string errorOf(const std::function<void()>& call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::vector<float> renderThree(SmokeSimulation& simulation, SmokeRenderer& renderer) {
  renderer.setCamera(sceneCamera());
  for (int frame = 0; frame < 3; ++frame) simulation.advance();
  renderer.render();
  return renderer.image();
}

TEST(FromMemory, TheSameSmokeAsFromTheFiles) {
  Device device({.validate = true});
  SmokeSimulation fromFile(device, kScene);
  SmokeRenderer rendererFromFile(device, fromFile, {.weights = kWeights});
  const std::vector<float> expected = renderThree(fromFile, rendererFromFile);

  const std::string scene = text(kScene);
  const std::vector<std::byte> weights = bytes(kWeights);
  SmokeSimulation fromMemory(device, SceneText{.json = scene});
  SmokeRenderer rendererFromMemory(device, fromMemory, {.weightsData = weights});
  EXPECT_EQ(renderThree(fromMemory, rendererFromMemory), expected);

  LightmapNetwork network(device, kWeights, 32), networkFromMemory(device, std::span(weights), 32);
  std::vector<float> guide(32 * 32 * 4, 0.25f);
  EXPECT_EQ(networkFromMemory.run(guide), network.run(guide));
  EXPECT_EQ(device.validationMessages(), 0u);
}

TEST(FromMemory, ErrorsNameWhatTheEngineCalledThem) {
  Device device;
  const std::string broken = "{\"grid\": ";
  EXPECT_EQ(errorOf([&] {
              SmokeSimulation s(device, SceneText{.json = broken, .name = "level3/smoke"});
            }).rfind("level3/smoke: ", 0),
            0u);
  EXPECT_EQ(
      errorOf([&] { SmokeSimulation s(device, SceneText{.json = broken}); }).rfind("scene in memory: ", 0),
      0u);

  // A mesh is looked for in the directory the engine gives.
  nlohmann::json withMesh = nlohmann::json::parse(text(kScene));
  withMesh["obstacles"] = {{{"type", "mesh"}, {"file", "rocks/boulder.obj"}}};
  const std::string meshScene = withMesh.dump();
  const std::string missing =
      errorOf([&] { SmokeSimulation s(device, SceneText{.json = meshScene, .directory = "/levels/three"}); });
  EXPECT_NE(missing.find("/levels/three/rocks/boulder.obj"), std::string::npos) << missing;

  std::vector<std::byte> weights = bytes(kWeights);
  weights.resize(weights.size() / 2);
  SmokeSimulation simulation(device, kScene);
  const std::string truncated =
      errorOf([&] { SmokeRenderer r(device, simulation, {.weightsData = weights}); });
  EXPECT_EQ(truncated.rfind("weights in memory: ", 0), 0u) << truncated;
  const std::string named = errorOf([&] {
    SmokeRenderer r(device, simulation, {.weights = "packs/smoke.pak#unet", .weightsData = weights});
  });
  EXPECT_EQ(named.rfind("packs/smoke.pak#unet: ", 0), 0u) << named;
}

TEST(FromMemory, TheCApiTakesTextAndBytes) {
  SixwayDevice device = nullptr;
  ASSERT_EQ(sixwayCreateOwnDevice(1, &device), SIXWAY_SUCCESS) << sixwayLastError();
  const std::string scene = text(kScene);
  const std::vector<std::byte> weights = bytes(kWeights);
  SixwaySimulation simulation = nullptr;
  EXPECT_EQ(sixwayCreateSimulationFromText(device, nullptr, 0, nullptr, &simulation),
            SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(sixwayCreateSimulationFromText(device, scene.data(), scene.size() - 10, nullptr, &simulation),
            SIXWAY_ERROR);
  EXPECT_EQ(std::string(sixwayLastError()).rfind("scene in memory: ", 0), 0u) << sixwayLastError();
  ASSERT_EQ(sixwayCreateSimulationFromText(device, scene.data(), scene.size(), nullptr, &simulation),
            SIXWAY_SUCCESS)
      << sixwayLastError();
  SixwayRenderer renderer = nullptr, sharing = nullptr;
  SixwayRendererInfo info{};
  info.weightsData = weights.data();
  info.weightsSize = 7;
  info.colorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
  EXPECT_EQ(sixwayCreateRendererFromInfo(device, simulation, &info, &renderer), SIXWAY_ERROR);
  EXPECT_EQ(std::string(sixwayLastError()).rfind("weights in memory: ", 0), 0u) << sixwayLastError();
  info.weightsSize = weights.size();
  EXPECT_EQ(sixwayCreateRendererFromInfo(device, simulation, &info, &renderer), SIXWAY_SUCCESS)
      << sixwayLastError();
  // A second renderer running the first one's network, inside the engine's rendering.
  SixwayRendererInfo shared{};
  EXPECT_EQ(sixwayCreateRendererFromInfo(device, simulation, &shared, &sharing),
            SIXWAY_ERROR_INVALID_ARGUMENT);
  const VkFormat colors[1] = {VK_FORMAT_R16G16B16A16_SFLOAT};
  shared.shareNetwork = renderer;
  shared.renderingColors = colors;
  shared.renderingColorCount = 1;
  shared.renderingDepth = VK_FORMAT_D32_SFLOAT;
  EXPECT_EQ(sixwayCreateRendererFromInfo(device, simulation, &shared, &sharing), SIXWAY_SUCCESS)
      << sixwayLastError();
  EXPECT_EQ(sixwayRendererRecordComposite(sharing, VK_NULL_HANDLE), SIXWAY_ERROR_INVALID_ARGUMENT)
      << "before recordLightmaps";
  sixwayDestroyRenderer(sharing);
  sixwayDestroyRenderer(renderer);
  sixwayDestroySimulation(simulation);
  sixwayDestroyDevice(device);
}

}  // namespace
}  // namespace sixway::test
