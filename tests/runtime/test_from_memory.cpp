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

#include <algorithm>
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

// A domain without a scene file is the scene file its fields name (written here by hand): the same smoke and
// image, fed by the engine's emitter and lit by its light; a value out of range is an Error naming its key.
TEST(FromMemory, ADomainIsTheSceneFileItsFieldsName) {
  Device device({.validate = true});
  const SmokeDomain domain{.cells = {16, 24, 20},
                           .cellSize = 0.05f,
                           .origin = {-0.4f, 0.0f, -0.5f},
                           .frameSeconds = 0.05f,
                           .viscosity = 2e-5f,
                           .buoyancy = 3.0f,
                           .extinction = 30.0f,
                           .albedo = 0.8f,
                           .phaseG = 0.3f,
                           .dissipation = 0.1f,
                           .lightmapSize = 32};
  const std::string json = R"({"grid": {"size": [16, 24, 20], "cell_size": 0.05, "origin": [-0.4, 0.0, -0.5]},
      "time": {"frame_dt": 0.05},
      "fluid": {"viscosity": 2e-5, "buoyancy": {"temperature": 3.0}},
      "smoke": {"extinction": 30.0, "albedo": 0.8, "phase_g": 0.3, "dissipation": 0.1},
      "camera": {"position": [0, 0.6, 2], "target": [0, 0.6, 0]},
      "render": {"lightmap_size": 32}})";
  BorrowingEngine engine(device);
  const auto frames = [&](SmokeSimulation& simulation) {
    EngineTargets targets(engine.context, 64, 64);
    SmokeRenderer renderer(engine.device, simulation, {.weights = kWeights}, targets.target());
    renderer.setCamera(sceneCamera());
    renderer.setLights({{.direction = {0.3f, 1.0f, 0.2f}, .intensity = 3.0f}});
    simulation.setEmitters({{.position = {0.0f, 0.15f, 0.0f}, .radius = 0.1f, .temperatureRate = 2.0f}});
    const float background[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    recordFrames(engine, targets, simulation, renderer, background);
    return targets.colorPixels();
  };
  SmokeSimulation fromDomain(engine.device, domain), fromText(engine.device, SceneText{.json = json});
  const std::vector<float> image = frames(fromDomain);
  EXPECT_EQ(maxDifference(image, frames(fromText)), 0.0);
  float brightest = 0.0f;  // over the black background
  for (size_t i = 0; i < image.size(); i += 4)
    brightest = std::max({brightest, image[i], image[i + 1], image[i + 2]});
  EXPECT_GT(brightest, 0.01f) << "no smoke";
  const std::string error = errorOf([&] { SmokeSimulation(device, SmokeDomain{.cells = {16, 0, 16}}); });
  EXPECT_NE(error.find("smoke domain"), std::string::npos) << error;
  EXPECT_NE(error.find("grid.size"), std::string::npos) << error;
  EXPECT_EQ(device.validationMessages(), 0u);
}

}  // namespace
}  // namespace sixway::test
