// Smoke instances that share one loaded network (RendererOptions::shareNetwork): each gives the image it
// gives with a network of its own, its own scene's albedo included, while the frames of the instances
// interleave; the second instance costs the network's memory less; networks of other lightmap sizes are
// refused.
#include <gtest/gtest.h>
#include <sixway/device.h>
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>

#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "runtime/engine_harness.h"
#include "support/temp_dir.h"

namespace sixway::test {
namespace {

// A network whose input reads the smoke's albedo (docs/network-format.md).
const std::filesystem::path kAlbedoWeights =
    std::filesystem::path(SIXWAY_TEST_DATA_DIR) / "nn/albedo_input.safetensors";

std::filesystem::path patchedScene(const std::filesystem::path& dir, const char* name,
                                   const nlohmann::json& patch) {
  std::ifstream in(kScene);
  nlohmann::json scene = nlohmann::json::parse(in);
  scene.merge_patch(patch);
  const std::filesystem::path file = dir / name;
  std::ofstream(file) << scene.dump();
  return file;
}

TEST(SharedNetwork, EachInstanceGivesItsOwnSmokeWithOneNetwork) {
  TempDir dir;
  const std::filesystem::path darker =
      patchedScene(dir.path(), "darker.json", {{"smoke", {{"albedo", 0.6}}}});
  Device device({.validate = true});
  SmokeSimulation first(device, kScene), shared(device, darker), alone(device, darker);
  SmokeRenderer firstRenderer(device, first, {.weights = kAlbedoWeights});
  const uint64_t before = device.memoryUse().bytes;
  SmokeRenderer sharedRenderer(device, shared, {.weights = kAlbedoWeights, .shareNetwork = &firstRenderer});
  const uint64_t withShared = device.memoryUse().bytes;
  SmokeRenderer aloneRenderer(device, alone, {.weights = kAlbedoWeights});
  const uint64_t withAlone = device.memoryUse().bytes;
  for (SmokeRenderer* r : {&firstRenderer, &sharedRenderer, &aloneRenderer}) r->setCamera(sceneCamera());
  // Frames interleaved: the shared network runs for the first scene, then the darker one, each frame.
  for (int frame = 0; frame < 3; ++frame) {
    for (SmokeSimulation* s : {&first, &shared, &alone}) s->advance();
    for (SmokeRenderer* r : {&firstRenderer, &sharedRenderer, &aloneRenderer}) r->render();
  }
  EXPECT_EQ(sharedRenderer.image(), aloneRenderer.image());
  EXPECT_GT(maxDifference(firstRenderer.image(), sharedRenderer.image()), 1e-3)
      << "the albedo changes nothing";
  const uint64_t sharedBytes = withShared - before, aloneBytes = withAlone - withShared;
  EXPECT_LT(sharedBytes, aloneBytes);
  std::cout << "[ measured ] a renderer sharing the network " << sharedBytes << " bytes, with its own "
            << aloneBytes << "\n";
  EXPECT_EQ(device.validationMessages(), 0u);
}

TEST(SharedNetwork, OnlyLightmapsOfOneSizeShareIt) {
  TempDir dir;
  const std::filesystem::path larger =
      patchedScene(dir.path(), "larger.json", {{"render", {{"lightmap_size", 64}}}});
  Device device;
  SmokeSimulation first(device, kScene), other(device, larger);
  SmokeRenderer firstRenderer(device, first, {.weights = kWeights});
  EXPECT_THROW(SmokeRenderer(device, other, {.weights = kWeights, .shareNetwork = &firstRenderer}),
               std::invalid_argument);
}

}  // namespace
}  // namespace sixway::test
