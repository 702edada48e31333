// The public API (include/sixway/) against the neural mode of `sixway render` (modes::ModeRenderer), and the
// engine path against sixway's own: the same smoke, the same pixels, and no host waits per frame when an
// engine records.
#include <gtest/gtest.h>
#include <sixway/device.h>
#include <sixway/errors.h>
#include <sixway/lightmap_network.h>
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <functional>
#include <glm/gtc/packing.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/check.h"
#include "gpu/device_features.h"
#include "gpu/image.h"
#include "io/safetensors.h"
#include "modes/mode_renderer.h"
#include "render/scene_frame.h"
#include "runtime/engine_harness.h"
#include "runtime/internal.h"
#include "runtime/scene_lights.h"
#include "runtime/scene_volumes.h"
#include "scene/fluid_physics.h"
#include "scene/scene.h"
#include "support/engine_projections.h"
#include "support/temp_dir.h"

namespace sixway::test {
namespace {

// The neural mode's frame 1 of small_plume with `weights`, simulated afresh on the device.
std::vector<float> neuralModeFrame(Device& device, const std::filesystem::path& weights) {
  const gpu::Context& context = runtime::Access::context(device);
  const gpu::PipelineCache& cache = runtime::Access::pipelineCache(device);
  const scene::Scene scene = scene::loadScene(kScene);
  runtime::SimulatedVolumes volumes(context, cache, scene, 2);
  modes::ModeOptions options;
  options.weights = weights;
  modes::ModeRenderer renderer(context, cache, scene, options);
  return renderer.render(1, runtime::SimulatedVolumes::frameSeconds(scene, 1), volumes.volume(1))
      .image.pixels;
}

TEST(Runtime, OwnImageIsTheNeuralModesFrame) {
  Device device({.validate = true});
  SmokeSimulation simulation(device, kScene);
  SmokeRenderer renderer(device, simulation, {.weights = kWeights});
  for (int frame = 0; frame < 2; ++frame) simulation.advance();
  renderer.render();
  const std::vector<float> image = renderer.image();

  const std::vector<float> expected = neuralModeFrame(device, kWeights);
  ASSERT_EQ(image.size(), expected.size());
  EXPECT_EQ(maxDifference(image, expected), 0.0);
  EXPECT_GT(*std::max_element(image.begin(), image.end()), 0.05f) << "no smoke in the image";
  bool timedNetwork = false;
  for (const StageTime& t : renderer.stageTimes()) timedNetwork |= t.name == "network";
  EXPECT_TRUE(timedNetwork);
  EXPECT_EQ(device.validationMessages(), 0u);
}

double lightSum(const std::vector<float>& rgba) {
  double sum = 0.0;
  for (size_t i = 0; i < rgba.size(); i += 4) sum += rgba[i] + rgba[i + 1] + rgba[i + 2];
  return sum;
}

// An engine's own lights, a restart, and what the API reports: the simulation's stage times, notes for a
// light beyond the shadow atlas, the device memory (flat over a restart). With the shipped network: the
// tiny test network's lightmaps are not light. small_plume's smoke emits nothing, so the lightmaps an engine
// reads hold no emissive (docs/embedding.md), while they hold light.
TEST(Runtime, EngineLightsRestartAndReports) {
  Device device({.validate = true});
  SmokeSimulation simulation(device, kScene);
  EXPECT_TRUE(simulation.stageTimes().empty());
  RendererOptions options{.weights =
                              std::filesystem::path(SIXWAY_WEIGHTS_DIR) / "sixway-unet-ms.safetensors"};
  options.shadowedLights = 1;  // small_plume's two lights both cast shadows
  SmokeRenderer renderer(device, simulation, options);
  for (int frame = 0; frame < 2; ++frame) simulation.advance();
  renderer.render();
  const std::vector<float> sceneLit = renderer.image();
  ASSERT_EQ(renderer.notes().size(), 1u);
  float light = 0.0f, emissive = 0.0f;
  const std::vector<uint16_t> b = runtime::Access::frame(renderer).lightmaps().b.download<uint16_t>();
  for (size_t i = 0; i < b.size(); i += 4) {  // B = left, bottom, front, emissive
    light = std::max(light, glm::unpackHalf1x16(b[i]));
    emissive = std::max(emissive, std::abs(glm::unpackHalf1x16(b[i + 3])));
  }
  EXPECT_GT(light, 0.01f);
  EXPECT_EQ(emissive, 0.0f);
  const std::vector<StageTime> simTimes = simulation.stageTimes();
  ASSERT_EQ(simTimes.size(), 4u);
  double simulated = 0.0;
  for (const StageTime& t : simTimes) {
    EXPECT_EQ(t.name.rfind("sim/", 0), 0u) << t.name;
    simulated += t.milliseconds;
  }
  EXPECT_GT(simulated, 0.0);

  // The scene's lights of frame 1 (the directional one orbits), given by the engine: the same image.
  const scene::Scene scene = scene::loadScene(kScene);
  std::vector<Light> lights;
  for (const scene::Light& l : render::sceneLights(scene.lights, 1))
    lights.push_back(runtime::publicLight(l));
  renderer.setLights(lights);
  renderer.render();
  const std::vector<float> engineLit = renderer.image();
  EXPECT_LT(maxDifference(sceneLit, engineLit), 1e-3);

  // The shading is linear in the lights (over the same background, obstacles and ambient light).
  renderer.setLights({});
  renderer.render();
  const double dark = lightSum(renderer.image()), lit = lightSum(engineLit);
  std::vector<Light> brighter = lights;
  for (Light& l : brighter) l.intensity *= 2.0f;
  renderer.setLights(brighter);
  renderer.render();
  const double bright = lightSum(renderer.image());
  EXPECT_GT(lit - dark, 0.1 * lit) << "the lights add little";
  EXPECT_NEAR(bright - lit, lit - dark, 0.02 * (lit - dark));

  // A restart replays the same smoke into new buffers; the renderer follows.
  const Device::MemoryUse before = device.memoryUse();
  EXPECT_GT(before.bytes, 0u);
  simulation.restart();
  EXPECT_EQ(simulation.framesSimulated(), 0);
  EXPECT_TRUE(simulation.stageTimes().empty());
  for (int frame = 0; frame < 2; ++frame) simulation.advance();
  renderer.setLights(lights);
  renderer.render();
  EXPECT_EQ(maxDifference(renderer.image(), engineLit), 0.0);
  EXPECT_EQ(device.memoryUse().bytes, before.bytes);

  EXPECT_NEAR(glm::length(simulation.obstaclePosition(0) - glm::vec3(0.12f, 0.7f, 0.1f)), 0.0f, 1e-5f);
  EXPECT_THROW(simulation.obstaclePosition(1), std::invalid_argument);
  Light broken = lights[0];
  broken.intensity = std::nanf("");
  EXPECT_THROW(renderer.setLights({broken}), std::invalid_argument);
  broken = lights[0];
  broken.direction = glm::vec3(0.0f);
  EXPECT_THROW(renderer.setLights({broken}), std::invalid_argument);
  EXPECT_THROW(renderer.setLights(std::vector<Light>(renderer.maxLights() + 1)), std::invalid_argument);
  EXPECT_EQ(device.validationMessages(), 0u);
}

TEST(Runtime, AnEngineRecordsTheSameFramesWithoutHostWaits) {
  TempDir dir;
  const std::filesystem::path scene = sceneWithoutObstacles(dir.path());
  constexpr int kFrames = 4;

  Device own({.validate = true});
  SmokeSimulation ownSimulation(own, scene);
  SmokeRenderer ownRenderer(own, ownSimulation, {.weights = kWeights});
  ownRenderer.setCamera(sceneCamera());
  for (int frame = 0; frame < kFrames; ++frame) ownSimulation.advance();
  ownRenderer.render();
  const std::vector<float> expected = ownRenderer.image();

  // The "engine": the same Vulkan device, borrowed, with its own images and command buffers.
  BorrowingEngine engine(own);
  EngineTargets targets(engine.context, ownRenderer.width(), ownRenderer.height());
  SmokeSimulation simulation(engine.device, scene);
  SmokeRenderer renderer(engine.device, simulation, {.weights = kWeights}, targets.target());
  renderer.setCamera(sceneCamera());
  const float* background = &expected[0];  // the corner: background only

  uint64_t waitsAfterFirstFrame = 0;
  for (int frame = 0; frame < kFrames; ++frame) {
    VkCommandBuffer commands = engine.begin();
    targets.recordClear(commands, background);
    simulation.record(commands, uint64_t(frame));
    renderer.record(commands, uint64_t(frame));
    // The first frame records the passes once (allocations may upload); later frames only replay.
    if (frame == 0) waitsAfterFirstFrame = engine.device.hostWaits();
    engine.submitAndWait();
  }
  EXPECT_EQ(engine.device.hostWaits(), waitsAfterFirstFrame) << "sixway blocked the host in frames 1..3";

  const std::vector<float> image = targets.colorPixels();
  ASSERT_EQ(image.size(), expected.size());
  EXPECT_LT(maxDifference(image, expected), 1e-3);
  EXPECT_GT(*std::max_element(image.begin(), image.end()), 0.05f) << "no smoke in the image";
  EXPECT_FALSE(renderer.stageTimes().empty()) << "the times of an earlier frame should be in";
  EXPECT_EQ(own.validationMessages(), 0u);
}

// small_plume (without its obstacle) through an engine's own matrices (setViewProjection), three frames
// recorded into its target with a depth format; `wall`: the view depth of a wall over the left half of the
// frame, written into the depth buffer as the engine's pass would leave it (else the buffer is cleared).
struct EngineFrame {
  glm::mat4 projection;
  glm::mat4 view = glm::lookAtRH(sceneCamera().position, sceneCamera().target, sceneCamera().up);
  DepthConvention convention = DepthConvention::Standard;
  VkFormat depthFormat = VK_FORMAT_D32_SFLOAT;
  std::optional<double> wall;
};

std::vector<float> engineFrame(BorrowingEngine& engine, const std::filesystem::path& scene,
                               const EngineFrame& f, uint32_t width, uint32_t height) {
  EngineTargets targets(engine.context, width, height, f.depthFormat);
  std::vector<double> depth(size_t(width) * height, clearDepth(f.convention));
  if (f.wall)
    for (uint32_t y = 0; y < height; ++y)
      for (uint32_t x = 0; x < width / 2; ++x) depth[size_t(y) * width + x] = depthAt(f.projection, *f.wall);
  targets.uploadDepth(depth);
  SmokeSimulation simulation(engine.device, scene);
  SmokeRenderer renderer(engine.device, simulation, {.weights = kWeights}, targets.target());
  renderer.setViewProjection(f.view, f.projection);
  const float background[4] = {0.1f, 0.2f, 0.3f, 1.0f};
  recordFrames(engine, targets, simulation, renderer, background, false);
  const std::vector<float> image = targets.colorPixels();
  return image;
}

// The largest difference over the pixels of columns [x0, x1).
double maxDifferenceIn(const std::vector<float>& a, const std::vector<float>& b, uint32_t width, uint32_t x0,
                       uint32_t x1) {
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    const uint32_t x = uint32_t(i / 4 % width);
    if (x >= x0 && x < x1) worst = std::max(worst, double(std::abs(a[i] - b[i])));
  }
  return worst;
}

// The same smoke in front of and behind the same wall, whatever the engine's depth convention and format.
TEST(Runtime, AnEngineDepthConventionAndFormatGiveTheSameSmoke) {
  TempDir dir;
  const std::filesystem::path scene = sceneWithoutObstacles(dir.path());
  Device own({.validate = true});
  BorrowingEngine engine(own);
  const scene::Scene parsed = scene::loadScene(scene);
  const uint32_t width = uint32_t(parsed.render.width), height = uint32_t(parsed.render.height);
  const Camera camera = sceneCamera();
  auto projection = [&](DepthConvention convention) {
    return engineProjection(convention, glm::radians(camera.fovYDegrees), float(width) / float(height),
                            camera.near, camera.far);
  };
  constexpr double kWall = 2.4;  // through the middle of the smoke (the camera is 2.4 from its axis)
  const EngineFrame standard{.projection = projection(DepthConvention::Standard), .wall = kWall};
  const std::vector<float> expected = engineFrame(engine, scene, standard, width, height);
  EXPECT_GT(*std::max_element(expected.begin(), expected.end()), 0.2f) << "no smoke in the image";

  // The wall hides the smoke behind it on the left and nothing on the right.
  EngineFrame open = standard;
  open.wall.reset();
  const std::vector<float> unwalled = engineFrame(engine, scene, open, width, height);
  EXPECT_GT(maxDifferenceIn(expected, unwalled, width, 0, width / 2), 0.05) << "the wall hid nothing";
  EXPECT_LT(maxDifferenceIn(expected, unwalled, width, width / 2, width), 1e-6);

  struct Variant {
    const char* name;
    DepthConvention convention;
    VkFormat format;
  };
  for (const Variant& v :
       {Variant{"reversed", DepthConvention::Reversed, VK_FORMAT_D32_SFLOAT},
        Variant{"infinite reversed", DepthConvention::InfiniteReversed, VK_FORMAT_D32_SFLOAT},
        Variant{"infinite", DepthConvention::InfiniteStandard, VK_FORMAT_D32_SFLOAT},
        Variant{"D24S8", DepthConvention::Standard, VK_FORMAT_D24_UNORM_S8_UINT},
        Variant{"D24S8 reversed", DepthConvention::Reversed, VK_FORMAT_D24_UNORM_S8_UINT},
        Variant{"D16", DepthConvention::Standard, VK_FORMAT_D16_UNORM}}) {
    const EngineFrame f{.projection = projection(v.convention),
                        .convention = v.convention,
                        .depthFormat = v.format,
                        .wall = kWall};
    const double measured = psnr(engineFrame(engine, scene, f, width, height), expected);
    EXPECT_GE(measured, 80.0) << v.name;  // docs/embedding.md promises 60 dB; 98-111 dB measured
    std::printf("%s: %.1f dB against standard D32\n", v.name, measured);
  }

  // A TAA jitter of one pixel to the right moves the image by one pixel.
  EngineFrame jittered = open;
  jittered.projection[2][0] -= 2.0f / float(width);  // NDC x += offset · w / (−z_view) = −offset
  const std::vector<float> shifted = engineFrame(engine, scene, jittered, width, height);
  double worst = 0.0;
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x + 1 < width; ++x)
      for (int c = 0; c < 4; ++c)
        worst = std::max(worst, double(std::abs(shifted[(size_t(y) * width + x + 1) * 4 + c] -
                                                unwalled[(size_t(y) * width + x) * 4 + c])));
  EXPECT_LT(worst, 1e-3);

  // A left-handed view and projection of sixway's right-handed world are a mirror camera: the same smoke,
  // mirrored left to right.
  EngineFrame mirror = open;
  mirror.view = glm::lookAtLH(camera.position, camera.target, camera.up);
  mirror.projection = vulkanY(glm::perspectiveLH_ZO(glm::radians(camera.fovYDegrees),
                                                    float(width) / float(height), camera.near, camera.far));
  const std::vector<float> mirrored = engineFrame(engine, scene, mirror, width, height);
  auto mirrorDifference = [&](const std::vector<float>& a, const std::vector<float>& b) {
    double largest = 0.0;
    for (uint32_t y = 0; y < height; ++y)
      for (uint32_t x = 0; x < width; ++x)
        for (int c = 0; c < 4; ++c)
          largest = std::max(largest, double(std::abs(a[(size_t(y) * width + width - 1 - x) * 4 + c] -
                                                      b[(size_t(y) * width + x) * 4 + c])));
    return largest;
  };
  EXPECT_GT(mirrorDifference(unwalled, unwalled), 0.05) << "the smoke is symmetric: no test of a mirror";
  EXPECT_LT(mirrorDifference(mirrored, unwalled), 1e-3);
  EXPECT_EQ(own.validationMessages(), 0u);
}

// An engine that shades the billboard itself gets the lightmaps and the world quad they cover: the smoke
// sixway draws lies inside that quad's projection.
TEST(Runtime, TheLightmapsQuadHoldsTheSmoke) {
  TempDir dir;
  const std::filesystem::path scene = sceneWithoutObstacles(dir.path());
  Device own({.validate = true});
  BorrowingEngine engine(own);
  const scene::Scene parsed = scene::loadScene(scene);
  const uint32_t width = uint32_t(parsed.render.width), height = uint32_t(parsed.render.height);
  EngineTargets targets(engine.context, width, height);
  SmokeSimulation simulation(engine.device, scene);
  SmokeRenderer renderer(engine.device, simulation, {.weights = kWeights}, targets.target());
  const Camera camera = sceneCamera();
  const glm::mat4 view = glm::lookAtRH(camera.position, camera.target, camera.up);
  const glm::mat4 projection = engineProjection(DepthConvention::Standard, glm::radians(camera.fovYDegrees),
                                                float(width) / float(height), camera.near, camera.far);
  renderer.setViewProjection(view, projection);
  const float transparent[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  recordFrames(engine, targets, simulation, renderer, transparent);
  const LightmapTextures maps = renderer.lightmaps();
  EXPECT_NE(maps.a, VK_NULL_HANDLE);
  EXPECT_NE(maps.b, VK_NULL_HANDLE);
  EXPECT_NE(maps.viewA, VK_NULL_HANDLE);
  EXPECT_NE(maps.viewB, VK_NULL_HANDLE);
  EXPECT_EQ(maps.format, VK_FORMAT_R16G16B16A16_SFLOAT);
  EXPECT_EQ(maps.width, runtime::Access::frame(renderer).lightmapSize());
  EXPECT_EQ(maps.height, maps.width);

  // The quad's corners in pixels (x right, y down), and the smoke's pixels (alpha over a clear target).
  glm::vec2 lo(1e9f), hi(-1e9f);
  for (const glm::vec3& corner : maps.corners) {
    const glm::vec4 clip = projection * view * glm::vec4(corner, 1.0f);
    const glm::vec2 pixel = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(width, height);
    lo = glm::min(lo, pixel);
    hi = glm::max(hi, pixel);
  }
  EXPECT_LT(maps.corners[0].y, maps.corners[3].y) << "the top edge is above the bottom one";
  const std::vector<float> image = targets.colorPixels();
  size_t smoke = 0, outside = 0;
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      if (image[(size_t(y) * width + x) * 4 + 3] <= 1e-3f) continue;
      ++smoke;
      const glm::vec2 centre(x + 0.5f, y + 0.5f);
      if (glm::any(glm::lessThan(centre, lo - 1.0f)) || glm::any(glm::greaterThan(centre, hi + 1.0f)))
        ++outside;
    }
  std::printf("quad [%.1f, %.1f] x [%.1f, %.1f], %zu smoke pixels\n", lo.x, hi.x, lo.y, hi.y, smoke);
  EXPECT_GT(smoke, 50u);
  EXPECT_EQ(outside, 0u) << "smoke outside the quad [" << lo.x << ", " << hi.x << "] x [" << lo.y << ", "
                         << hi.y << "]";
  EXPECT_EQ(own.validationMessages(), 0u);
}

// An engine that runs sixway's one-time work itself (EngineDevice::submitAndWait): sixway never submits or
// waits, from the device's creation on, and the frames are the same.
TEST(Runtime, AnEngineRunsSixwaysOneTimeWork) {
  TempDir dir;
  const std::filesystem::path scene = sceneWithoutObstacles(dir.path());
  Device own({.validate = true});
  EngineUploads uploads(runtime::Access::context(own));
  std::vector<float> images[2];
  for (int hooked = 0; hooked < 2; ++hooked) {
    BorrowingEngine engine(own, hooked ? uploads.submit() : nullptr);
    const scene::Scene parsed = scene::loadScene(scene);
    EngineTargets targets(engine.context, uint32_t(parsed.render.width), uint32_t(parsed.render.height));
    SmokeSimulation simulation(engine.device, scene);
    SmokeRenderer renderer(engine.device, simulation, {.weights = kWeights}, targets.target());
    renderer.setCamera(sceneCamera());
    const float background[4] = {0.1f, 0.2f, 0.3f, 1.0f};
    recordFrames(engine, targets, simulation, renderer, background);
    if (hooked) {
      EXPECT_EQ(engine.device.hostWaits(), 0u) << "sixway waited on the GPU itself";
    }
    images[hooked] = targets.colorPixels();
  }
  EXPECT_GT(uploads.calls, 0);
  EXPECT_EQ(maxDifference(images[0], images[1]), 0.0);
  EXPECT_EQ(own.validationMessages(), 0u);
}

// Steering an obstacle replaces the simulation's recorded steps while earlier frames may still be in flight
// or unread; frame numbers may skip. Every frame's measurements still arrive, and nothing trips validation.
TEST(Runtime, AnEngineSteersAnObstacleBetweenFrames) {
  Device own({.validate = true});
  BorrowingEngine engine(own);
  SmokeSimulation simulation(engine.device, kScene);
  ASSERT_EQ(simulation.obstacleCount(), 1u);
  for (uint64_t frame : {0, 1, 2, 5, 6, 9, 10, 11}) {
    if (frame == 5) simulation.steerObstacle(0, {-0.1f, 0.6f, 0.0f});
    simulation.record(engine.begin(), frame);
    engine.submitAndWait();
  }
  EXPECT_EQ(simulation.framesSimulated(), 8);
  // The stage times of an earlier recorded frame have come back.
  const std::vector<StageTime> times = simulation.stageTimes();
  ASSERT_EQ(times.size(), 4u);
  EXPECT_EQ(times[1].name, "sim/lbm");
  EXPECT_GT(times[1].milliseconds, 0.0);
  const SmokeVolume volume = simulation.volume();
  EXPECT_NE(volume.density, VK_NULL_HANDLE);
  EXPECT_EQ(volume.cells, glm::ivec3(24, 32, 24) * scene::loadScene(kScene).grid.smokeUpres);
  EXPECT_FLOAT_EQ(volume.cellSize, 0.04f / float(scene::loadScene(kScene).grid.smokeUpres));
  // The measurements read so far are of frames recorded two frames before the last ones: the smoke is there.
  const sim::AdvanceReport& report = runtime::Access::volumes(simulation).simulation().report();
  EXPECT_GT(report.smokeMass, 0.0);
  EXPECT_EQ(report.forces.size(), size_t(scene::lbmStepsPerFrame(scene::loadScene(kScene))));
  EXPECT_EQ(own.validationMessages(), 0u);
}

TEST(Runtime, ErrorsNameTheFile) {
  Device device;
  try {
    SmokeSimulation simulation(device, "no_such_scene.json");
    FAIL() << "a missing scene was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "no_such_scene.json: no such file");
  }
  SmokeSimulation simulation(device, kScene);
  try {
    SmokeRenderer renderer(device, simulation, {.weights = "missing.safetensors"});
    FAIL() << "missing weights were accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "missing.safetensors: no such weights file");
  }
  try {
    LightmapNetwork network(device, kScene, 16);
    FAIL() << "a scene file was accepted as weights";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("small_plume.json: "), std::string::npos) << e.what();
  }
}

// The tiny network made to read the guide's 4th channel as the fine alpha of `step` voxels (its input
// convolution already takes 4 channels; the 4th was zero).
std::filesystem::path fineAlphaNetwork(const std::filesystem::path& dir, float step) {
  io::SafetensorsFile file = io::readSafetensors(kWeights);
  nlohmann::json graph = nlohmann::json::parse(file.metadata.at("sixway.graph"));
  graph["nodes"][0]["guide_channels"] = 4;
  graph["nodes"][0]["guide_alpha_step_voxels"] = step;
  file.metadata["sixway.graph"] = graph.dump();
  const std::filesystem::path path = dir / "fine_alpha.safetensors";
  io::writeSafetensors(path, file.tensors, file.metadata);
  return path;
}

// A network that reads the fine alpha turns it on in the frame's guiding map, in the public renderer and in
// the neural mode alike (same pixels), and its frame differs from the 3-channel network's.
TEST(Runtime, ANetworkThatReadsTheFineAlphaGetsIt) {
  TempDir dir;
  const std::filesystem::path weights = fineAlphaNetwork(dir.path(), 1.0f);
  Device device({.validate = true});
  SmokeSimulation simulation(device, kScene);
  SmokeRenderer renderer(device, simulation, {.weights = weights});
  EXPECT_FLOAT_EQ(runtime::Access::frame(renderer).guiding().settings().alphaStepCells, 1.0f);
  for (int frame = 0; frame < 2; ++frame) simulation.advance();
  renderer.render();
  const std::vector<float> image = renderer.image();

  EXPECT_EQ(maxDifference(image, neuralModeFrame(device, weights)), 0.0);
  EXPECT_GT(maxDifference(image, neuralModeFrame(device, kWeights)), 1e-3);

  EXPECT_FLOAT_EQ(LightmapNetwork(device, weights, 16).fineAlphaStepVoxels(), 1.0f);
  EXPECT_FLOAT_EQ(LightmapNetwork(device, kWeights, 16).fineAlphaStepVoxels(), 0.0f);
  EXPECT_EQ(device.validationMessages(), 0u);
}

TEST(Runtime, TheNetworkAloneGivesEightChannels) {
  Device device({.validate = true});
  LightmapNetwork network(device, kWeights, 16);
  std::vector<float> guide(16 * 16 * 4, 0.0f);
  for (size_t i = 0; i < 16 * 16; ++i) guide[i * 4 + 0] = guide[i * 4 + 1] = 0.5f;
  const std::vector<float> lightmaps = network.run(guide);
  ASSERT_EQ(lightmaps.size(), size_t(16 * 16 * 8));
  for (float v : lightmaps) ASSERT_TRUE(std::isfinite(v));
  EXPECT_EQ(device.validationMessages(), 0u);
}

// A network whose guide has the emission as a 5th channel reads it from run()'s second argument, and refuses
// to run without it; one without refuses an emission it would not read.
TEST(Runtime, TheNetworkAloneTakesTheEmissionItReads) {
  Device device({.validate = true});
  LightmapNetwork emitting(device,
                           std::filesystem::path(SIXWAY_TEST_DATA_DIR) / "nn/emission_guide.safetensors", 16);
  LightmapNetwork plain(device, kWeights, 16);
  EXPECT_TRUE(emitting.readsEmission());
  EXPECT_FALSE(plain.readsEmission());
  std::vector<float> guide(16 * 16 * 4, 0.0f), dark(16 * 16, 0.0f), glowing(16 * 16, 0.0f);
  for (size_t i = 0; i < 16 * 16; ++i) {
    guide[i * 4 + 0] = guide[i * 4 + 1] = guide[i * 4 + 3] = 0.5f;
    glowing[i] = 0.05f * float(i % 16);
  }
  EXPECT_THROW(emitting.run(guide), std::invalid_argument);
  EXPECT_THROW(plain.run(guide, glowing), std::invalid_argument);
  const std::vector<float> withoutGlow = emitting.run(guide, dark), withGlow = emitting.run(guide, glowing);
  ASSERT_EQ(withGlow.size(), size_t(16 * 16 * 8));
  for (float v : withGlow) ASSERT_TRUE(std::isfinite(v));
  EXPECT_GT(maxDifference(withGlow, withoutGlow), 1e-4) << "the emission is read";
  EXPECT_EQ(device.validationMessages(), 0u);
}

// A network that reads the smoke's albedo takes it from run()'s third argument, within [0, 1].
TEST(Runtime, TheNetworkAloneTakesTheAlbedoItReads) {
  Device device({.validate = true});
  LightmapNetwork network(device, std::filesystem::path(SIXWAY_TEST_DATA_DIR) / "nn/albedo_input.safetensors",
                          16);
  EXPECT_TRUE(network.readsAlbedo());
  EXPECT_FALSE(LightmapNetwork(device, kWeights, 16).readsAlbedo());
  std::vector<float> guide(16 * 16 * 4, 0.0f), emission(16 * 16, 0.0f);
  for (size_t i = 0; i < 16 * 16; ++i) guide[i * 4 + 0] = guide[i * 4 + 1] = guide[i * 4 + 3] = 0.5f;
  EXPECT_THROW(network.run(guide, emission, 1.2f), std::invalid_argument);
  const std::vector<float> grey = network.run(guide, emission, 0.8f),
                           white = network.run(guide, emission, 0.95f);
  EXPECT_GT(maxDifference(grey, white), 1e-4) << "the albedo is read";
  EXPECT_EQ(network.run(guide, emission, 0.8f), grey) << "and set again for each run";
  EXPECT_EQ(device.validationMessages(), 0u);
}

// The two networks of weights/ (weights/README.md): trained on the all-orders and the single-scattering
// targets, both reading the 1-cell fine alpha and passing it through as their alpha, and both reading the
// guide's emission: the single-scattering one passes it through as its emissive (its target is that direct
// emission); each runs under validation.
TEST(Runtime, TheShippedNetworksAreBothTruthsWithTheFineAlphaPassedThrough) {
  Device device({.validate = true});
  for (const auto& [name, target] : {std::pair{"ms", "multiple"}, std::pair{"ss", "single"}}) {
    const std::filesystem::path weights =
        std::filesystem::path(SIXWAY_WEIGHTS_DIR) / ("sixway-unet-" + std::string(name) + ".safetensors");
    const nlohmann::json training =
        nlohmann::json::parse(io::readSafetensors(weights).metadata.at("sixway.training"));
    EXPECT_EQ(training["config"]["data"]["target"], target) << weights;
    EXPECT_EQ(training["config"]["model"]["alpha"], "guide") << weights;

    constexpr uint32_t size = 64;
    LightmapNetwork network(device, weights, size);
    EXPECT_FLOAT_EQ(network.fineAlphaStepVoxels(), 1.0f) << weights;
    const bool emissionPassedThrough = std::string(name) == "ss";
    EXPECT_EQ(training["config"]["model"].value("emissive", "network"),
              emissionPassedThrough ? "guide" : "network")
        << weights;
    ASSERT_TRUE(network.readsEmission()) << weights;
    std::vector<float> guide(size * size * 4), emission(size * size);
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x) {
        const float r = std::hypot(float(x) - 32.0f, float(y) - 32.0f) / 24.0f;  // a disk of smoke
        const float alpha = std::clamp(1.0f - r, 0.0f, 1.0f);
        float* g = &guide[(y * size + x) * 4];
        g[0] = 0.6f * alpha, g[1] = alpha, g[2] = alpha > 0.0f ? 0.5f : 1.0f, g[3] = alpha;
        emission[y * size + x] = 0.3f * alpha * alpha;  // a glowing core
      }
    const std::vector<float> lightmaps = network.run(guide, emission);
    ASSERT_EQ(lightmaps.size(), size_t(size * size * 8));
    double alphaError = 0.0, emissionError = 0.0;
    for (size_t i = 0; i < size_t(size * size); ++i) {
      for (int c = 0; c < 8; ++c) ASSERT_TRUE(std::isfinite(lightmaps[i * 8 + c])) << weights;
      // The guide map is RGBA16F, as the runtime's own: the alpha passed through is the half-rounded value.
      const float fineAlpha = glm::unpackHalf1x16(glm::packHalf1x16(guide[i * 4 + 3]));
      alphaError = std::max(alphaError, double(std::abs(lightmaps[i * 8 + 6] - fineAlpha)));
      // Relative, over the glowing core: the network's input map holds half floats, rounded as the driver
      // rounds (an ulp is at most 2^-10 of the value).
      if (emission[i] > 0.01f)
        emissionError =
            std::max(emissionError, double(std::abs(lightmaps[i * 8 + 7] - emission[i]) / emission[i]));
    }
    EXPECT_LT(alphaError, 1e-5) << weights << ": the alpha is the guide's fine alpha";
    if (emissionPassedThrough)
      EXPECT_LT(emissionError, 2e-3) << weights << ": the emissive is the guide's emission";
    else
      EXPECT_GT(emissionError, 1e-2) << weights << ": the emissive is the network's";
  }
  EXPECT_EQ(device.validationMessages(), 0u);
}

}  // namespace
}  // namespace sixway::test
