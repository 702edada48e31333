#include "scene/scene.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/error.h"
#include "io/json_reader.h"
#include "scene/fluid_physics.h"
#include "support/temp_dir.h"

namespace sixway::scene {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::TempDir;

// Wall-clock bound of the parsing tests, stretched in AddressSanitizer builds (tools/sanitize.sh): the 24 MB
// of keyframes took 18 s there with both cores loaded.
#ifdef __SANITIZE_ADDRESS__
constexpr double kSeconds = 8.0 * 5.0;
#else
constexpr double kSeconds = 5.0;
#endif

// Only the required keys.
json minimalScene() {
  return R"({
    "grid": {"size": [16, 32, 16], "cell_size": 0.05},
    "fluid": {"viscosity": 1.5e-5},
    "camera": {"position": [0, 1, 3], "target": [0, 1, 0]}
  })"_json;
}

// The minimal scene with `patch` merged in (RFC 7386: objects merge, arrays and values replace).
json minimalWith(const json& patch) {
  json scene = minimalScene();
  scene.merge_patch(patch);
  return scene;
}

void writeFile(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

// The message must be one line: "<source>: <key>: <reason...>".
::testing::AssertionResult namesKeyAndReason(const std::string& message, const std::string& source,
                                             const std::string& key, const std::string& reason) {
  const std::string prefix = source + ": " + key + ": ";
  if (message.rfind(prefix, 0) != 0)
    return ::testing::AssertionFailure() << "\"" << message << "\" does not start with \"" << prefix << "\"";
  if (message.find(reason, prefix.size()) == std::string::npos)
    return ::testing::AssertionFailure() << "\"" << message << "\" does not say \"" << reason << "\"";
  if (message.find('\n') != std::string::npos)
    return ::testing::AssertionFailure() << "\"" << message << "\" is more than one line";
  return ::testing::AssertionSuccess();
}

std::string errorOf(const std::function<void()>& load) {
  try {
    load();
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

::testing::AssertionResult rejected(const json& scene, const std::string& key, const std::string& reason,
                                    const fs::path& baseDir = ".") {
  const std::string message = errorOf([&] { parseScene(scene, "scenes/bad.json", baseDir); });
  return namesKeyAndReason(message, "scenes/bad.json", key, reason);
}

void expectVec(const glm::vec3& actual, const glm::vec3& expected) {
  EXPECT_NEAR(actual.x, expected.x, 1e-6f);
  EXPECT_NEAR(actual.y, expected.y, 1e-6f);
  EXPECT_NEAR(actual.z, expected.z, 1e-6f);
}

// --- valid scenes ---------------------------------------------------------------------------------

TEST(SceneTest, ShippedPlumeLoads) {
  const Scene s = loadScene(fs::path(SIXWAY_ASSETS_DIR) / "scenes" / "plume.json");
  EXPECT_EQ(s.name, "plume");
  EXPECT_EQ(s.grid.size, glm::ivec3(64, 128, 64));
  EXPECT_FLOAT_EQ(s.grid.cellSize, 0.025f);
  expectVec(s.grid.origin, {-0.8f, 0, -0.8f});
  EXPECT_EQ(s.boundaries.faces[Boundaries::YMinus], BoundaryType::NoSlip);
  EXPECT_EQ(s.boundaries.faces[Boundaries::YPlus], BoundaryType::Outflow);

  ASSERT_EQ(s.inlets.size(), 1u);
  const auto& disk = std::get<InletDisk>(s.inlets[0].shape);
  EXPECT_FLOAT_EQ(disk.radius, 0.1f);
  expectVec(disk.normal, {0, 1, 0});
  expectVec(s.inlets[0].velocity, {0, 1, 0});
  EXPECT_FLOAT_EQ(s.inlets[0].temperature, 1);
  EXPECT_GT(s.fluid.buoyancy.temperature, 0);  // a plume rises because it is hot

  ASSERT_EQ(s.obstacles.size(), 1u);
  const auto& cylinder = std::get<CylinderObstacle>(s.obstacles[0].shape);
  expectVec(cylinder.center, {0, 1.1f, 0});
  expectVec(cylinder.axis, {0, 0, 1});
  EXPECT_FALSE(s.obstacles[0].motion);

  ASSERT_EQ(s.lights.size(), 2u);
  const auto& sun = std::get<DirectionalLight>(s.lights[0].source);
  expectVec(sun.direction, glm::vec3(1, 1.5f, 0.5f) / std::sqrt(1 + 2.25f + 0.25f));
  ASSERT_TRUE(s.lights[0].path);
  EXPECT_FLOAT_EQ(s.lights[0].path->degreesPerFrame, 1);
  EXPECT_TRUE(std::holds_alternative<PointLight>(s.lights[1].source));
  EXPECT_FALSE(s.lights[1].path);

  expectVec(s.camera.position, {0, 1.4f, 4.5f});
  EXPECT_FLOAT_EQ(s.camera.fovDeg, 45);
  EXPECT_TRUE(s.ambient && std::holds_alternative<AmbientColor>(*s.ambient));
  EXPECT_EQ(s.render.width, 512);
  EXPECT_FLOAT_EQ(kinematicViscosity(s), 1.5e-5f);
  // The inflow alone needs 14 (1 m/s · (1/30 s / 14) / 2.5 cm = 0.095 ≤ 0.1); the buoyant plume's bound
  // sqrt(2 · 2 m/s² · 3.2 m) = 3.58 m/s needs ceil(3.58 · (1/30) / (0.25 · 0.025)) = 20.
  EXPECT_NEAR(buoyantSpeedBound(s), 3.5777f, 1e-3f);
  EXPECT_EQ(lbmStepsPerFrame(s), 20);
}

// The default run's scene starts after a warm-up and shows its frames through the ACES fit.
TEST(SceneTest, ShowcaseWarmsUpAndToneMaps) {
  const Scene s = loadScene(fs::path(SIXWAY_ASSETS_DIR) / "scenes" / "showcase.json");
  EXPECT_EQ(s.render.warmupFrames, 90);
  EXPECT_EQ(s.render.toneMap, ToneMap::Aces);
  EXPECT_FLOAT_EQ(s.render.exposureStops, 0.5f);
  ASSERT_TRUE(s.camera.path);
  EXPECT_EQ(s.obstacles.size(), 1u);
  const Scene plain = parseScene(minimalScene(), "minimal.json", ".");
  EXPECT_EQ(plain.render.warmupFrames, 0);
  EXPECT_EQ(plain.render.toneMap, ToneMap::Clamp);
  EXPECT_EQ(plain.render.exposureStops, 0.0f);
}

TEST(SceneParse, BadDisplaySettings) {
  EXPECT_TRUE(rejected(minimalWith(R"({"render": {"tone_map": "filmic"}})"_json), "render.tone_map",
                       "must be one of \"clamp\", \"aces\" (got \"filmic\")"));
  EXPECT_TRUE(rejected(minimalWith(R"({"render": {"exposure": 40}})"_json), "render.exposure",
                       "must be in [-20, 20] (got 40)"));
  EXPECT_TRUE(rejected(minimalWith(R"({"render": {"warmup_frames": -1}})"_json), "render.warmup_frames",
                       "must be in [0, 100000] (got -1)"));
}

TEST(SceneParse, SparseSmokeSettings) {
  const Scene s = parseScene(minimalWith(R"({"smoke": {"sparse": false, "sparse_threshold": 0}})"_json),
                             "minimal.json", ".");
  EXPECT_FALSE(s.smoke.sparse);
  EXPECT_EQ(s.smoke.sparseThreshold, 0.0f);
  EXPECT_TRUE(rejected(minimalWith(R"({"smoke": {"sparse_threshold": -1e-6}})"_json),
                       "smoke.sparse_threshold", "must be"));
  EXPECT_TRUE(rejected(minimalWith(R"({"smoke": {"sparse": "yes"}})"_json), "smoke.sparse", ""));
}

TEST(SceneTest, MinimalSceneGetsDefaults) {
  const Scene s = parseScene(minimalScene(), "scenes/minimal.json", ".");
  EXPECT_EQ(s.name, "minimal");
  EXPECT_EQ(s.grid.size, glm::ivec3(16, 32, 16));
  expectVec(s.grid.origin, {0, 0, 0});
  EXPECT_EQ(s.grid.smokeUpres, 1);
  EXPECT_FLOAT_EQ(s.time.frameDt, 1.0f / 30);
  EXPECT_EQ(s.time.stepsPerFrame, 4);

  EXPECT_FLOAT_EQ(*s.fluid.viscosity, 1.5e-5f);
  EXPECT_FALSE(s.fluid.reynolds);
  EXPECT_FLOAT_EQ(s.fluid.smagorinsky, 0.1f);
  EXPECT_FLOAT_EQ(s.fluid.maxLatticeVelocity, 0.1f);
  EXPECT_EQ(s.fluid.obstacleBoundary, ObstacleBoundary::HalfWay);
  EXPECT_EQ(s.fluid.buoyancy.temperature, 0);
  EXPECT_EQ(s.fluid.buoyancy.density, 0);
  expectVec(s.fluid.gravity, {0, -9.81f, 0});

  for (int face = 0; face < 6; ++face)
    EXPECT_EQ(s.boundaries.faces[face],
              face == Boundaries::YMinus ? BoundaryType::NoSlip : BoundaryType::Outflow);
  expectVec(s.boundaries.wind, {0, 0, 0});
  EXPECT_TRUE(s.inlets.empty());
  EXPECT_TRUE(s.obstacles.empty());

  EXPECT_FLOAT_EQ(s.smoke.extinction, 20);
  EXPECT_FLOAT_EQ(s.smoke.albedo, 0.9f);
  EXPECT_FLOAT_EQ(s.smoke.phaseG, 0.2f);
  EXPECT_EQ(s.smoke.dissipation, 0);
  EXPECT_TRUE(s.smoke.sparse);
  EXPECT_FLOAT_EQ(s.smoke.sparseThreshold, 1e-6f);
  EXPECT_EQ(s.smoke.emission.intensity, 0);
  EXPECT_TRUE(s.smoke.emission.ramp.empty());

  expectVec(s.camera.up, {0, 1, 0});
  EXPECT_FLOAT_EQ(s.camera.fovDeg, 40);
  EXPECT_FALSE(s.camera.path);
  EXPECT_TRUE(s.lights.empty());
  EXPECT_FALSE(s.ambient);

  EXPECT_EQ(s.render.width, 256);
  EXPECT_EQ(s.render.height, 256);
  EXPECT_EQ(s.render.lightmapSize, 128);
  EXPECT_FLOAT_EQ(s.render.guideStepVoxels, 3);
  EXPECT_FLOAT_EQ(s.render.guideAlphaStepVoxels, 0);
  EXPECT_EQ(s.render.guideLights, (std::vector{GuideLight::Front, GuideLight::Top, GuideLight::Bottom}));
  expectVec(s.render.background, {0, 0, 0});
  EXPECT_FLOAT_EQ(s.render.shellThreshold, 0.1f);
  EXPECT_EQ(s.render.seed, 1u);

  EXPECT_EQ(lbmStepsPerFrame(s), 4);  // nothing flows in
}

TEST(SceneTest, OtherShapesLightsAndPathsAreRead) {
  const Scene s = parseScene(minimalWith(R"({
    "boundaries": {"x-": "inflow", "z-": "periodic", "z+": "periodic", "wind": [2, 0, 0]},
    "inlets": [{"shape": "box", "min": [0, 0, 0], "max": [0.1, 0.1, 0.1], "velocity": [0, 0.5, 0],
                "start": 1, "stop": 2}],
    "obstacles": [{"type": "sphere", "center": [0.4, 0.4, 0.4], "radius": 0.1, "shadows": false},
                  {"type": "box", "size": [0.1, 0.2, 0.3],
                   "motion": {"keyframes": [{"time": 0, "position": [1, 2, 3]},
                                            {"time": 1, "position": [1, 3, 3]}], "loop": true}}],
    "smoke": {"emission": {"intensity": 2, "ramp": [{"temperature": 0, "color": [0, 0, 0]},
                                                    {"temperature": 1, "color": [4, 1, 0]}]}},
    "camera": {"up": [0, 2, 0], "path": {"type": "dolly", "end_position": [0, 1, 2], "frames": 60}},
    "lights": [{"type": "point", "position": [1, 1, 1],
                "path": {"type": "orbit", "center": [0, 1, 0], "degrees_per_frame": 2}}],
    "ambient": {"sh": [[0.1, 0.1, 0.1], [0, 0, 0], [0, 0.05, 0], [0, 0, 0]]},
    "render": {"guide_lights": ["front", "left", "right"], "seed": 4000000000, "guide_alpha_step_voxels": 0.5}
  })"_json),
                             "s.json", ".");
  EXPECT_EQ(s.boundaries.faces[Boundaries::XMinus], BoundaryType::Inflow);
  EXPECT_EQ(s.boundaries.faces[Boundaries::ZPlus], BoundaryType::Periodic);
  expectVec(s.inlets[0].velocity, {0, 0.5f, 0});
  EXPECT_FLOAT_EQ(s.inlets[0].stop, 2);
  EXPECT_FLOAT_EQ(referenceSpeed(s), 2);  // the wind is faster than the inlet

  EXPECT_FALSE(s.obstacles[0].shadows);
  const auto& box = std::get<BoxObstacle>(s.obstacles[1].shape);
  expectVec(box.center, {1, 2, 3});  // the first keyframe
  EXPECT_TRUE(s.obstacles[1].motion->loop);

  EXPECT_EQ(s.smoke.emission.ramp.size(), 2u);
  expectVec(s.camera.up, {0, 1, 0});
  EXPECT_EQ(std::get<CameraDolly>(*s.camera.path).frames, 60);
  EXPECT_FLOAT_EQ(s.lights[0].intensity, std::numbers::pi_v<float>);
  expectVec(s.lights[0].path->center, {0, 1, 0});
  EXPECT_FLOAT_EQ(std::get<AmbientSh>(*s.ambient).coefficients[2].y, 0.05f);
  EXPECT_EQ(s.render.guideLights, (std::vector{GuideLight::Front, GuideLight::Left, GuideLight::Right}));
  EXPECT_EQ(s.render.seed, 4000000000u);
  EXPECT_FLOAT_EQ(s.render.guideAlphaStepVoxels, 0.5f);
}

TEST(SceneTest, ReynoldsUsesTheFastestInlet) {
  const Scene s = parseScene(minimalWith(R"({
    "fluid": {"viscosity": null, "reynolds": 1000, "reference_length": 0.2, "max_lattice_velocity": 0.1},
    "inlets": [{"shape": "disk", "center": [0.4, 0.1, 0.4], "radius": 0.1, "normal": [0, 3, 0], "velocity": 1},
               {"shape": "disk", "center": [0.4, 0.1, 0.4], "radius": 0.1, "normal": [0, 1, 0], "velocity": 2}]
  })"_json),
                             "s.json", ".");
  expectVec(std::get<InletDisk>(s.inlets[0].shape).normal, {0, 1, 0});
  EXPECT_FLOAT_EQ(referenceSpeed(s), 2);
  EXPECT_FLOAT_EQ(kinematicViscosity(s), 2 * 0.2f / 1000);
  EXPECT_EQ(lbmStepsPerFrame(s), 14);  // ceil(2 m/s · 1/30 s / (0.1 · 0.05 m)) = ceil(13.3)
}

TEST(SceneTest, ObstacleBoundaryIsRead) {
  const auto boundary = [](const char* name) {
    return parseScene(minimalWith({{"fluid", {{"obstacle_boundary", name}}}}), "s.json", ".")
        .fluid.obstacleBoundary;
  };
  EXPECT_EQ(boundary("half_way"), ObstacleBoundary::HalfWay);
  EXPECT_EQ(boundary("interpolated"), ObstacleBoundary::Interpolated);
}

TEST(SceneTest, PopulationStorageIsRead) {
  const auto storage = [](const nlohmann::json& fluid) {
    return parseScene(minimalWith({{"fluid", fluid}}), "s.json", ".").fluid.populationStorage;
  };
  EXPECT_EQ(storage(nlohmann::json::object()), PopulationStorage::Fp32);  // the default
  EXPECT_EQ(storage({{"population_storage", "fp32"}}), PopulationStorage::Fp32);
  EXPECT_EQ(storage({{"population_storage", "fp16"}}), PopulationStorage::Fp16);
}

TEST(SceneTest, MeshPathIsResolvedAgainstTheSceneFile) {
  TempDir dir;
  writeFile(dir / "meshes" / "rock.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  json scene = minimalWith(R"({"obstacles": [{"type": "mesh", "file": "../meshes/rock.obj", "scale": 2,
                                              "rotate_deg": [0, 90, 0]}]})"_json);
  writeFile(dir / "scenes" / "rocky.json", scene.dump(2));

  const Scene s = loadScene(dir / "scenes" / "rocky.json");
  const auto& mesh = std::get<MeshObstacle>(s.obstacles[0].shape);
  EXPECT_EQ(mesh.file, fs::absolute(dir / "meshes" / "rock.obj").lexically_normal());
  EXPECT_TRUE(mesh.file.is_absolute());
  EXPECT_FLOAT_EQ(mesh.scale, 2);
  expectVec(mesh.rotateDeg, {0, 90, 0});
}

// A scene that plays back three files written into `dir`/vdb (empty: existence is all the parser checks).
json vdbScene(const fs::path& dir) {
  for (int i = 1; i <= 3; ++i) writeFile(dir / "vdb" / ("smoke_00" + std::to_string(i) + ".vdb"), "");
  return R"({
    "vdb": {"pattern": "vdb/smoke_%03d.vdb", "first": 1, "last": 3},
    "camera": {"position": [0, 1, 3], "target": [0, 1, 0]}
  })"_json;
}

TEST(SceneTest, VdbSceneReadsFilesAndDefaults) {
  TempDir dir;
  json j = vdbScene(dir.path());
  j["smoke"] = {
      {"emission",
       {{"intensity", 2.0},
        {"ramp", {{{"temperature", 0}, {"color", {0, 0, 0}}}, {{"temperature", 1}, {"color", {1, 1, 1}}}}}}}};
  j["vdb"].update(R"({"temperature_grid": "heat", "density_scale": 0.5, "frames_per_file": 4, "voxels": 64,
                      "scale": 0.01, "translate": [1, 2, 3], "up": "z",
                      "box_min": [-1, 0, -1], "box_max": [1, 2, 1]})"_json);
  const Scene s = parseScene(j, "v.json", dir.path());
  ASSERT_TRUE(s.vdb);
  ASSERT_EQ(s.vdb->files.size(), 3u);
  EXPECT_EQ(s.vdb->files[1], fs::absolute(dir / "vdb" / "smoke_002.vdb").lexically_normal());
  EXPECT_EQ(s.vdb->densityGrid, "density");
  EXPECT_EQ(s.vdb->temperatureGrid, "heat");
  EXPECT_FLOAT_EQ(s.vdb->densityScale, 0.5f);
  EXPECT_EQ(s.vdb->framesPerFile, 4);
  EXPECT_EQ(s.vdb->voxels, 64);
  EXPECT_FLOAT_EQ(s.vdb->scale, 0.01f);
  expectVec(s.vdb->translate, {1, 2, 3});
  EXPECT_EQ(s.vdb->up, VdbUp::Z);
  ASSERT_TRUE(s.vdb->box);
  expectVec(s.vdb->box->second, {1, 2, 1});
  EXPECT_EQ(sceneFrameCount(s), 12);
  EXPECT_TRUE(s.inlets.empty());
  EXPECT_THAT(errorOf([&] { requireSimulated(s, "v.json"); }),
              ::testing::HasSubstr("v.json: the scene plays back vdb files"));

  j.erase("smoke");  // emission needs the temperature grid the list below leaves out
  j["vdb"] = {{"files", {"vdb/smoke_003.vdb", "vdb/smoke_001.vdb"}}};
  const Scene listed = parseScene(j, "v.json", dir.path());
  EXPECT_EQ(listed.vdb->files[0].filename(), "smoke_003.vdb");
  EXPECT_EQ(listed.vdb->up, VdbUp::Y);
  EXPECT_FALSE(listed.vdb->box);
  EXPECT_EQ(sceneFrameCount(listed), 2);

  j["vdb"]["voxels"] = "native";
  EXPECT_EQ(parseScene(j, "v.json", dir.path()).vdb->voxels, kNativeVoxels);
  j["vdb"]["voxels"] = "all";
  EXPECT_THAT(errorOf([&] { parseScene(j, "v.json", dir.path()); }),
              ::testing::HasSubstr("vdb.voxels: must be one of \"native\" (got \"all\")"));
}

TEST(SceneParse, VdbSceneRefusesWhatOnlySimulationUses) {
  TempDir dir;
  const json base = vdbScene(dir.path());
  for (const char* key : {"grid", "fluid", "boundaries", "inlets", "obstacles"}) {
    json j = base;
    j[key] = json::object();
    EXPECT_TRUE(rejected(j, key, "plays back vdb files", dir.path())) << key;
  }
  json j = base;
  j["time"] = {{"steps_per_frame", 4}};
  EXPECT_TRUE(rejected(j, "time.steps_per_frame", "plays back vdb files", dir.path()));
  j = base;
  j["smoke"] = {{"dissipation", 0.1}};
  EXPECT_TRUE(rejected(j, "smoke.dissipation", "plays back vdb files", dir.path()));
  j = base;
  j["smoke"] = {{"sparse_threshold", 0.0}};
  EXPECT_TRUE(rejected(j, "smoke.sparse_threshold", "plays back vdb files", dir.path()));
  j = base;
  j["smoke"] = {
      {"emission",
       {{"intensity", 1.0},
        {"ramp", {{{"temperature", 0}, {"color", {0, 0, 0}}}, {{"temperature", 1}, {"color", {1, 1, 1}}}}}}}};
  EXPECT_TRUE(rejected(j, "smoke.emission", "name the grid with vdb.temperature_grid", dir.path()));
}

TEST(SceneParse, BadVdbSections) {
  TempDir dir;
  const json base = vdbScene(dir.path());
  auto with = [&](const json& vdb) {
    json j = base;
    j["vdb"] = vdb;
    return j;
  };
  EXPECT_TRUE(rejected(with(json::object()), "vdb", "give either \"files\"", dir.path()));
  EXPECT_TRUE(
      rejected(with({{"files", {"a.vdb"}}, {"pattern", "b_%d.vdb"}}), "vdb", "give either", dir.path()));
  EXPECT_TRUE(rejected(with({{"files", json::array()}}), "vdb.files", "needs 1 to", dir.path()));
  const fs::path missing = fs::absolute(dir / "vdb" / "smoke_004.vdb").lexically_normal();
  EXPECT_TRUE(rejected(with({{"pattern", "vdb/smoke_%03d.vdb"}, {"first", 2}, {"last", 4}}), "vdb.pattern",
                       "vdb file not found: " + missing.string(), dir.path()));
  EXPECT_TRUE(rejected(with({{"files", {"vdb/none.vdb"}}}), "vdb.files", "vdb file not found", dir.path()));
  EXPECT_TRUE(rejected(with({{"pattern", "vdb/smoke_001.vdb"}, {"first", 1}, {"last", 1}}), "vdb.pattern",
                       "exactly one %d", dir.path()));
  EXPECT_TRUE(rejected(with({{"pattern", "vdb/%d_%d.vdb"}, {"first", 1}, {"last", 1}}), "vdb.pattern",
                       "exactly one %d", dir.path()));
  EXPECT_TRUE(rejected(with({{"pattern", "vdb/smoke_%03d.vdb"}, {"first", 3}, {"last", 1}}), "vdb.last",
                       "must be in", dir.path()));
  EXPECT_TRUE(rejected(with({{"files", {"vdb/smoke_001.vdb"}}, {"first", 1}}), "vdb.first",
                       "only used with \"pattern\"", dir.path()));
  EXPECT_TRUE(rejected(with({{"files", {"vdb/smoke_001.vdb"}}, {"up", "x"}}), "vdb.up", "must be one of",
                       dir.path()));
  EXPECT_TRUE(rejected(with({{"files", {"vdb/smoke_001.vdb"}}, {"density_scale", 0}}), "vdb.density_scale",
                       "must be > 0", dir.path()));
  EXPECT_TRUE(rejected(with({{"files", {"vdb/smoke_001.vdb"}}, {"voxels", 4096}}), "vdb.voxels", "must be in",
                       dir.path()));
  EXPECT_TRUE(rejected(with({{"files", {"vdb/smoke_001.vdb"}}, {"density_grid", ""}}), "vdb.density_grid",
                       "must name a grid", dir.path()));
  EXPECT_TRUE(rejected(with({{"files", {"vdb/smoke_001.vdb"}}, {"box_min", {0, 0, 0}}}), "vdb.box_max",
                       "go together", dir.path()));
  EXPECT_TRUE(
      rejected(with({{"files", {"vdb/smoke_001.vdb"}}, {"box_min", {0, 0, 0}}, {"box_max", {1, 0, 1}}}),
               "vdb.box_max", "must exceed box_min", dir.path()));
}

// --- one test per kind of error -------------------------------------------------------------------

TEST(SceneParse, UnknownTopLevelKey) {
  EXPECT_TRUE(
      rejected(minimalWith(R"({"lightz": []})"_json), "lightz", "unknown key (did you mean \"lights\"?)"));
}

TEST(SceneParse, UnknownNestedKey) {
  EXPECT_TRUE(rejected(minimalWith(R"({"fluid": {"viscosity": null, "viscosty": 1e-5}})"_json),
                       "fluid.viscosty", "unknown key (did you mean \"viscosity\"?)"));
}

TEST(SceneParse, UnknownKeyInArrayElement) {
  const json scene = minimalWith(R"({"obstacles": [
    {"type": "sphere", "center": [0, 0, 0], "radius": 0.1},
    {"type": "sphere", "center": [0, 0, 0], "radius": 0.1, "height": 0.3}]})"_json);
  EXPECT_TRUE(rejected(scene, "obstacles[1].height", "unknown key"));
}

TEST(SceneParse, MisspeltRequiredKeyIsPointedOut) {
  const json scene =
      minimalWith(R"({"obstacles": [{"type": "sphere", "center": [0, 0, 0], "radus": 0.1}]})"_json);
  EXPECT_TRUE(rejected(scene, "obstacles[0].radius", "required key missing (is \"radus\" a typo?)"));
}

TEST(SceneParse, StringForNumber) {
  EXPECT_TRUE(rejected(minimalWith(R"({"smoke": {"albedo": "0.5"}})"_json), "smoke.albedo",
                       "expected a number (got \"0.5\")"));
}

TEST(SceneParse, TwoElementVector) {
  EXPECT_TRUE(rejected(minimalWith(R"({"grid": {"size": [64, 64]}})"_json), "grid.size",
                       "expected an array of 3 integers (got [64,64])"));
  EXPECT_TRUE(rejected(minimalWith(R"({"camera": {"position": [0, 1]}})"_json), "camera.position",
                       "expected an array of 3 numbers"));
}

TEST(SceneParse, FractionForInteger) {
  EXPECT_TRUE(
      rejected(minimalWith(R"({"render": {"width": 256.5}})"_json), "render.width", "expected an integer"));
}

TEST(SceneParse, ScalarForObject) {
  EXPECT_TRUE(rejected(minimalWith(R"({"smoke": 3})"_json), "smoke", "expected an object (got 3)"));
}

TEST(SceneParse, TopLevelNotAnObject) {
  const std::string message = errorOf([] { parseScene(json::array(), "scenes/bad.json", "."); });
  EXPECT_EQ(message, "scenes/bad.json: expected an object (got [])");
}

TEST(SceneParse, MissingRequiredKey) {
  json scene = minimalScene();
  scene.erase("camera");
  EXPECT_TRUE(rejected(scene, "camera.position", "required key missing"));
  scene = minimalScene();
  scene["grid"].erase("cell_size");
  EXPECT_TRUE(rejected(scene, "grid.cell_size", "required key missing"));
}

TEST(SceneParse, UnknownChoice) {
  EXPECT_TRUE(
      rejected(minimalWith(R"({"obstacles": [{"type": "cone"}]})"_json), "obstacles[0].type",
               "must be one of \"sphere\", \"cylinder\", \"capsule\", \"box\", \"mesh\" (got \"cone\")"));
}

TEST(SceneParse, UnknownObstacleBoundary) {
  EXPECT_TRUE(rejected(minimalWith(R"({"fluid": {"obstacle_boundary": "bouzidi"}})"_json),
                       "fluid.obstacle_boundary",
                       "must be one of \"half_way\", \"interpolated\" (got \"bouzidi\")"));
}

TEST(SceneParse, UnknownPopulationStorage) {
  EXPECT_TRUE(rejected(minimalWith(R"({"fluid": {"population_storage": "bf16"}})"_json),
                       "fluid.population_storage", "must be one of \"fp32\", \"fp16\" (got \"bf16\")"));
}

TEST(SceneParse, NegativeRadius) {
  const json scene = minimalWith(R"({"obstacles": [
    {"type": "sphere", "center": [0, 0, 0], "radius": 0.1},
    {"type": "sphere", "center": [0, 0, 0], "radius": -0.5}]})"_json);
  EXPECT_TRUE(rejected(scene, "obstacles[1].radius", "must be > 0 (got -0.5)"));
}

TEST(SceneParse, AlbedoOutOfRange) {
  EXPECT_TRUE(rejected(minimalWith(R"({"smoke": {"albedo": 1.5}})"_json), "smoke.albedo",
                       "must be in [0, 1] (got 1.5)"));
}

// A light colour of 3.4e38 would give inf/NaN pixels; numbers a float cannot hold must be named as such, not
// reported as "expected a number" (1e308) or read as 0 and then "must be > 0 (got 0)" (1e-308).
TEST(SceneParse, NumbersBeyondWhatAFrameCanHold) {
  EXPECT_TRUE(rejected(minimalWith(R"({"lights": [{"type": "point", "position": [0, 0, 0],
                                                   "color": [3.4e38, 1, 1]}]})"_json),
                       "lights[0].color", "every component must be in [0, 10000]"));
  EXPECT_TRUE(rejected(
      minimalWith(R"({"lights": [{"type": "point", "position": [0, 0, 0], "intensity": 1e5}]})"_json),
      "lights[0].intensity", "must be in [0, 10000] (got 100000)"));
  EXPECT_TRUE(rejected(minimalWith(R"({"smoke": {"extinction": 1e308}})"_json), "smoke.extinction",
                       "is beyond the range of a 32-bit float, ±3.4e38 (got 1e+308)"));
  EXPECT_TRUE(rejected(minimalWith(R"({"smoke": {"extinction": 1e-308}})"_json), "smoke.extinction",
                       "is too small for a 32-bit float, which would make it 0 (got 1e-308)"));
  EXPECT_TRUE(rejected(minimalWith(R"({"camera": {"position": [0, 1e300, 3]}})"_json), "camera.position",
                       "is beyond the range of a 32-bit float"));
  EXPECT_TRUE(rejected(minimalWith(R"({"camera": {"position": [0, 1e20, 3]}})"_json), "camera.position",
                       "every component must be in [-1000000, 1000000] (got [0, 1e+20, 3])"));
  EXPECT_TRUE(
      rejected(minimalWith(R"({"ambient": {"sh": [[1, 1, 1], [0, 0, 0], [0, -2e4, 0], [0, 0, 0]]}})"_json),
               "ambient.sh", "every component must be in [-10000, 10000] (got [0, -20000, 0])"));
}

// Unity's light-probe L1 is 2/3 of the radiance's; "unity_probe" takes it as it is.
TEST(SceneParse, AmbientShInUnitysProbeConvention) {
  const json radiance =
      minimalWith(R"({"ambient": {"sh": [[1, 1, 1], [0.3, 0, 0], [0, 0.6, 0], [0, 0, -0.9]]}})"_json);
  json unity = radiance;
  unity["ambient"]["sh_convention"] = "unity_probe";
  const auto a = std::get<AmbientSh>(*parseScene(radiance, "r.json", ".").ambient).coefficients;
  const auto b = std::get<AmbientSh>(*parseScene(unity, "u.json", ".").ambient).coefficients;
  EXPECT_EQ(b[0], a[0]);
  for (int i = 1; i < 4; ++i) EXPECT_EQ(b[i], 1.5f * a[i]) << i;
  EXPECT_TRUE(
      rejected(minimalWith(R"({"ambient": {"color": [1, 1, 1], "sh_convention": "unity_probe"}})"_json),
               "ambient.sh_convention", "goes with sh, not color"));
}

TEST(SceneParse, LightmapSizeNotMultipleOf16) {
  EXPECT_TRUE(rejected(minimalWith(R"({"render": {"lightmap_size": 100}})"_json), "render.lightmap_size",
                       "must be a multiple of 16 (got 100)"));
}

TEST(SceneParse, NegativeColorComponent) {
  EXPECT_TRUE(rejected(minimalWith(R"({"lights": [{"type": "point", "position": [0, 0, 0],
                                                   "color": [1, -1, 1]}]})"_json),
                       "lights[0].color", "every component must be in [0, 10000] (got [1, -1, 1])"));
}

TEST(SceneParse, BothViscosityAndReynolds) {
  EXPECT_TRUE(rejected(minimalWith(R"({"fluid": {"reynolds": 100, "reference_length": 1}})"_json), "fluid",
                       "give exactly one of viscosity and reynolds, not both"));
}

TEST(SceneParse, NeitherViscosityNorReynolds) {
  EXPECT_TRUE(rejected(minimalWith(R"({"fluid": {"viscosity": null}})"_json), "fluid",
                       "give exactly one of viscosity (m²/s) and reynolds"));
}

TEST(SceneParse, ReynoldsWithoutAnythingFlowingIn) {
  EXPECT_TRUE(rejected(minimalWith(R"({"fluid": {"viscosity": null, "reynolds": 100,
                                                 "reference_length": 1}})"_json),
                       "fluid.reynolds", "needs a reference speed"));
}

TEST(SceneParse, UnpairedPeriodic) {
  EXPECT_TRUE(rejected(minimalWith(R"({"boundaries": {"x-": "periodic"}})"_json), "boundaries.x-",
                       "periodic needs the opposite face periodic too (x+ is not)"));
}

TEST(SceneParse, InflowWithoutWind) {
  EXPECT_TRUE(rejected(minimalWith(R"({"boundaries": {"z-": "inflow"}})"_json), "boundaries.wind",
                       "required key missing (face z- is inflow)"));
}

TEST(SceneParse, KeyframeTimesNotIncreasing) {
  const json scene = minimalWith(R"({"obstacles": [{"type": "sphere", "radius": 0.1, "motion": {"keyframes": [
    {"time": 0, "position": [0, 0, 0]}, {"time": 1.5, "position": [1, 0, 0]},
    {"time": 1, "position": [2, 0, 0]}]}}]})"_json);
  EXPECT_TRUE(rejected(scene, "obstacles[0].motion.keyframes[2].time",
                       "keyframe times must increase: got 1 after 1.5"));
}

TEST(SceneParse, CenterOfMovingObstacle) {
  const json scene = minimalWith(R"({"obstacles": [{"type": "sphere", "center": [0, 0, 0], "radius": 0.1,
    "motion": {"keyframes": [{"time": 0, "position": [0, 0, 0]},
                             {"time": 1, "position": [1, 0, 0]}]}}]})"_json);
  EXPECT_TRUE(rejected(scene, "obstacles[0].center", "not allowed (the motion keyframes give the position)"));
}

TEST(SceneParse, MissingMeshFile) {
  TempDir dir;
  const json scene = minimalWith(R"({"obstacles": [{"type": "mesh", "file": "meshes/none.obj"}]})"_json);
  const fs::path resolved = fs::absolute(dir / "meshes" / "none.obj").lexically_normal();
  EXPECT_TRUE(rejected(scene, "obstacles[0].file", "mesh file not found: " + resolved.string(), dir.path()));
}

TEST(SceneParse, AbsurdGrid) {
  EXPECT_TRUE(rejected(minimalWith(R"({"grid": {"size": [100000, 100000, 100000]}})"_json), "grid.size",
                       "axis x has 100000 cells, more than 2048; reduce grid.size"));
  EXPECT_TRUE(rejected(minimalWith(R"({"grid": {"size": [1024, 1024, 1024]}})"_json), "grid.size",
                       "1024×1024×1024 = 1073741824 cells, more than 512³; reduce grid.size"));
  EXPECT_TRUE(rejected(minimalWith(R"({"grid": {"size": [512, 512, 512], "smoke_upres": 4}})"_json),
                       "grid.smoke_upres", "more than 1024³; reduce grid.smoke_upres or grid.size"));
}

TEST(SceneParse, TooManyStepsPerFrame) {
  const json scene = minimalWith(R"({"time": {"frame_dt": 10},
    "inlets": [{"shape": "disk", "center": [0.4, 0.1, 0.4], "radius": 0.1, "normal": [0, 1, 0],
                "velocity": 100}]})"_json);
  EXPECT_TRUE(rejected(scene, "time.frame_dt", "LBM steps per frame"));
}

TEST(SceneParse, AbsurdStepsPerFrame) {
  EXPECT_TRUE(rejected(minimalWith(R"({"time": {"steps_per_frame": 1000000000}})"_json),
                       "time.steps_per_frame", "must be in [1, 10000] (got 1000000000)"));
}

// Lists beyond the shaders' fixed arrays are refused when the scene is read, not when a pass meets them.
TEST(SceneParse, MoreListEntriesThanTheShadersHold) {
  auto repeated = [](const json& element, std::size_t count) {
    return json(std::vector<json>(count, element));
  };
  const json light = R"({"type": "point", "position": [0, 1, 0]})"_json;
  EXPECT_TRUE(rejected(minimalWith({{"lights", repeated(light, kMaxSceneLights + 1)}}), "lights",
                       "at most 8 elements are supported (got 9)"));
  EXPECT_NO_THROW(parseScene(minimalWith({{"lights", repeated(light, kMaxSceneLights)}}), "ok.json", "."));
  const json sphere = R"({"type": "sphere", "center": [0, 0.5, 0], "radius": 0.1})"_json;
  EXPECT_TRUE(rejected(minimalWith({{"obstacles", repeated(sphere, kMaxSceneObstacles + 1)}}), "obstacles",
                       "at most 16 elements are supported (got 17)"));
  const json inlet =
      R"({"shape": "disk", "center": [0, 0, 0], "radius": 0.1, "normal": [0, 1, 0], "velocity": 0.1})"_json;
  EXPECT_TRUE(rejected(minimalWith({{"inlets", repeated(inlet, kMaxSceneInlets + 1)}}), "inlets",
                       "at most 8 elements are supported (got 9)"));
  json ramp = json::array();
  for (std::size_t i = 0; i <= kMaxRampKeys; ++i) ramp.push_back({{"temperature", i}, {"color", {1, 1, 1}}});
  EXPECT_TRUE(rejected(minimalWith({{"smoke", {{"emission", {{"intensity", 1}, {"ramp", ramp}}}}}}),
                       "smoke.emission.ramp", "at most 16 elements are supported (got 17)"));
}

// An inlet that marks no cell of the grid gave smokeless frames without a word, and a disk of radius 1e30
// overflowed the simulation's integer box of inlet cells. The grid here spans [0, 0, 0] to [0.8, 1.6, 0.8] m
// in cells of 0.05 m.
TEST(SceneParse, InletsMustEmitIntoTheGrid) {
  const auto withInlet = [](const json& inlet) { return minimalWith({{"inlets", json::array({inlet})}}); };
  const auto disk = [](glm::vec3 center, double radius) {
    return json{{"shape", "disk"},
                {"center", {center.x, center.y, center.z}},
                {"radius", radius},
                {"normal", {0, 1, 0}},
                {"velocity", 0.5}};
  };
  const auto box = [](glm::vec3 lo, glm::vec3 hi) {
    return json{{"shape", "box"}, {"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}};
  };
  EXPECT_TRUE(rejected(withInlet(disk({0.4f, -0.5f, 0.4f}, 0.1)), "inlets[0]",
                       "covers no cell of the grid, which spans [0, 0, 0] to [0.8, 1.6, 0.8] m in cells of "
                       "0.05 m: no smoke would enter"));
  EXPECT_TRUE(rejected(withInlet(disk({0.4f, 0.1f, 0.4f}, 1e30)), "inlets[0].radius",
                       "must be at most the grid's diagonal"));
  EXPECT_TRUE(rejected(withInlet(box({5, 5, 5}, {6, 6, 6})), "inlets[0]", "covers no cell of the grid"));
  // Thinner than a cell and between two cell centres (x = 0.075 and 0.125).
  EXPECT_TRUE(rejected(withInlet(box({0.08f, 0.1f, 0.1f}, {0.12f, 0.2f, 0.2f})), "inlets[0]",
                       "covers no cell of the grid"));
  // A disk on the grid's floor (its slab, half a cell either side of y = 0, holds no cell centre) emits
  // nothing.
  EXPECT_TRUE(rejected(withInlet(disk({0.4f, 0, 0.4f}, 0.1)), "inlets[0]", "covers no cell of the grid"));
  // Partly outside is fine: a disk centred over the grid's corner edge, a box reaching far past the grid.
  EXPECT_NO_THROW(parseScene(withInlet(disk({0, 0.1f, 0}, 0.1)), "ok.json", "."));
  EXPECT_NO_THROW(parseScene(withInlet(box({-1e5f, -1e5f, -1e5f}, {0.1f, 0.1f, 0.1f})), "ok.json", "."));
  EXPECT_NO_THROW(parseScene(withInlet(disk({0.4f, 0.1f, 0.4f}, 1.9)), "ok.json", "."));
}

TEST(SceneParse, CameraTargetEqualsPosition) {
  EXPECT_TRUE(rejected(minimalWith(R"({"camera": {"target": [0, 1, 3]}})"_json), "camera.target",
                       "must differ from camera.position"));
}

TEST(SceneParse, CameraUpAlongView) {
  EXPECT_TRUE(rejected(minimalWith(R"({"camera": {"up": [0, 0, -1]}})"_json), "camera.up",
                       "must not be parallel to the view direction"));
}

TEST(SceneParse, DuplicateGuideLight) {
  EXPECT_TRUE(rejected(minimalWith(R"({"render": {"guide_lights": ["front", "top", "front"]}})"_json),
                       "render.guide_lights[2]", "\"front\" is listed twice"));
}

TEST(SceneParse, GuideAlphaStepOutOfRange) {
  EXPECT_TRUE(rejected(minimalWith(R"({"render": {"guide_alpha_step_voxels": -1}})"_json),
                       "render.guide_alpha_step_voxels", "must be 0 or in [0.05, 16] (got -1)"));
}

// A step of a billionth of a cell never advances a float ray; one of 1e30 cells steps past the smoke: either
// gave an empty guide, and the smoke vanished.
TEST(SceneParse, GuideStepsWithinWhatAMarchCanTake) {
  EXPECT_TRUE(rejected(minimalWith(R"({"render": {"guide_step_voxels": 1e-9}})"_json),
                       "render.guide_step_voxels", "must be in [0.05, 16] (got 1e-09)"));
  EXPECT_TRUE(rejected(minimalWith(R"({"render": {"guide_step_voxels": 1e30}})"_json),
                       "render.guide_step_voxels", "must be in [0.05, 16] (got 1e+30)"));
  EXPECT_TRUE(rejected(minimalWith(R"({"render": {"guide_alpha_step_voxels": 1e-9}})"_json),
                       "render.guide_alpha_step_voxels", "must be 0 or in [0.05, 16] (got 1e-09)"));
  const Scene fine = parseScene(
      minimalWith(R"({"render": {"guide_step_voxels": 0.05, "guide_alpha_step_voxels": 16}})"_json),
      "ok.json", ".");
  EXPECT_FLOAT_EQ(fine.render.guideStepVoxels, 0.05f);
  EXPECT_FLOAT_EQ(fine.render.guideAlphaStepVoxels, 16.0f);
  EXPECT_EQ(parseScene(minimalWith(R"({"render": {"guide_alpha_step_voxels": 0}})"_json), "ok.json", ".")
                .render.guideAlphaStepVoxels,
            0.0f);
}

// A box beyond a float's range made the renderers' light-grid loops spin forever (the diagonal was inf): the
// lattice's box and every placement are bounded by kMaxSceneMetres.
TEST(SceneParse, BoxesWithinTheScenesReach) {
  EXPECT_TRUE(rejected(minimalWith(R"({"grid": {"cell_size": 1e30}})"_json), "grid.cell_size",
                       "16×32×16 cells of 1e+30 m make a box of more than 1000000 m along an axis; reduce "
                       "grid.cell_size"));
  EXPECT_TRUE(rejected(minimalWith(R"({"grid": {"cell_size": 62500}})"_json), "grid.cell_size",
                       "more than 1000000 m along an axis"));
  EXPECT_NO_THROW(parseScene(minimalWith(R"({"grid": {"cell_size": 31250}})"_json), "ok.json", "."));
  EXPECT_TRUE(rejected(minimalWith(R"({"grid": {"origin": [0, -1e30, 0]}})"_json), "grid.origin",
                       "every component must be in [-1000000, 1000000]"));
  TempDir dir;
  const json vdb = vdbScene(dir.path());
  for (const char* patch : {R"({"vdb": {"scale": 1e30}})", R"({"vdb": {"translate": [1e30, 0, 0]}})",
                            R"({"vdb": {"box_min": [-1e30, 0, 0], "box_max": [1, 1, 1]}})"}) {
    json j = vdb;
    j.merge_patch(json::parse(patch));
    EXPECT_THAT(errorOf([&] { parseScene(j, "scenes/bad.json", dir.path()); }),
                ::testing::MatchesRegex("scenes/bad.json: vdb\\.[a-z_]+: .*must be in .*1000000.*"))
        << patch;
  }
}

TEST(SceneParse, ZeroDirection) {
  EXPECT_TRUE(rejected(minimalWith(R"({"lights": [{"type": "directional", "direction": [0, 0, 0]}]})"_json),
                       "lights[0].direction", "must not be the zero vector"));
}

// --- errors reading the file ---------------------------------------------------------------------

TEST(SceneTest, InvalidJsonNamesLineAndColumn) {
  TempDir dir;
  const fs::path file = dir / "broken.json";
  writeFile(file, "{\n  \"grid\": {\"size\": [16, 16, 16]},\n  \"fluid\": {\"viscosity\" 1e-5}\n}\n");
  const std::string message = errorOf([&] { loadScene(file); });
  EXPECT_EQ(message.rfind(file.string() + ": invalid JSON: ", 0), 0u) << message;
  EXPECT_NE(message.find("line 3, column"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

// Found by fuzzing (tests/fuzz/): a number beyond double is nlohmann's out_of_range, not a parse_error, and
// escaped parseJsonText.
TEST(SceneTest, NumberBeyondDoubleIsInvalidJson) {
  const fs::path file = fs::path(SIXWAY_TEST_DATA_DIR) / "fuzz" / "scene_number_overflow.json";
  const std::string message = errorOf([&] { loadScene(file); });
  EXPECT_EQ(message, file.string() + ": invalid JSON: number overflow parsing '0.033e333'");
}

TEST(SceneTest, DuplicateJsonKeyNamesItsPath) {
  TempDir dir;
  const fs::path file = dir / "twice.json";
  writeFile(file, R"({"lights": [{"type": "point", "position": [0, 0, 0]},
                                 {"type": "point", "color": [1, 1, 1], "color": [1, 0, 0]}]})");
  EXPECT_TRUE(namesKeyAndReason(errorOf([&] { loadScene(file); }), file.string(), "lights[1].color",
                                "key appears twice"));
}

// 70,000 nested arrays (140 KB) would crash an error path that printed the value recursively. A
// document nested past kMaxJsonNesting is refused while it is parsed, arrays and objects alike.
TEST(SceneTest, DeepNestingIsOneLineNotACrash) {
  TempDir dir;
  const int levels = 70000;
  const std::string arrays = std::string(levels, '[') + std::string(levels, ']');
  std::string objects;
  for (int i = 0; i < levels; ++i) objects += "{\"a\":";
  objects += "1" + std::string(levels, '}');
  for (const std::string& text : {arrays, objects}) {
    const fs::path file = dir / "deep.json";
    writeFile(file, text);
    EXPECT_EQ(errorOf([&] { loadScene(file); }),
              file.string() + ": JSON nested deeper than " + std::to_string(io::kMaxJsonNesting) + " levels");
  }
  // The limit itself is accepted: the error is then about the content (no grid).
  const fs::path file = dir / "at_limit.json";
  writeFile(file, "{\"a\":" + std::string(io::kMaxJsonNesting - 1, '[') +
                      std::string(io::kMaxJsonNesting - 1, ']') + "}");
  EXPECT_EQ(errorOf([&] { loadScene(file); }), file.string() + ": grid.size: required key missing");
}

// An array of 1,000,000 objects is parsed in time linear in its length and refused at its element count.
TEST(SceneTest, MillionElementArrayIsRefusedWithinSeconds) {
  TempDir dir;
  const fs::path file = dir / "million_lights.json";
  std::string lights;
  lights.reserve(3'000'000);
  for (int i = 0; i < 1'000'000; ++i) lights += i == 0 ? "{}" : ",{}";
  std::string text = minimalScene().dump();
  text.insert(text.size() - 1, ",\"lights\": [" + lights + "]");
  writeFile(file, text);
  const auto start = std::chrono::steady_clock::now();
  const std::string message = errorOf([&] { loadScene(file); });
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_EQ(message, file.string() + ": lights: at most 8 elements are supported (got 1000000)");
  EXPECT_LT(elapsed.count(), kSeconds);
}

// The same for an array without a count limit: each element is read in turn, the first one found wanting.
TEST(SceneTest, MillionKeyframesAreReadWithinSeconds) {
  TempDir dir;
  const fs::path file = dir / "million_keyframes.json";
  std::string keyframes;
  keyframes.reserve(24'000'000);
  for (int i = 0; i < 1'000'000; ++i)
    keyframes +=
        (i == 0 ? "" : ",") + std::string("{\"time\":") + std::to_string(i % 3) + ",\"position\":[0,1,0]}";
  json scene = minimalScene();
  scene["obstacles"] = json::array({{{"type", "sphere"}, {"radius", 0.1}, {"motion", {{"keyframes", 0}}}}});
  std::string text = scene.dump();
  const std::string placeholder = "\"keyframes\":0";
  text.replace(text.find(placeholder), placeholder.size(), "\"keyframes\":[" + keyframes + "]");
  writeFile(file, text);
  const auto start = std::chrono::steady_clock::now();
  const std::string message = errorOf([&] { loadScene(file); });
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_EQ(
      message,
      file.string() + ": obstacles[0].motion.keyframes[3].time: keyframe times must increase: got 0 after 2");
  EXPECT_LT(elapsed.count(), kSeconds);
}

TEST(SceneTest, MissingSceneFile) {
  TempDir dir;
  const fs::path file = dir / "nowhere.json";
  EXPECT_EQ(errorOf([&] { loadScene(file); }), file.string() + ": no such file");
}

}  // namespace
}  // namespace sixway::scene
