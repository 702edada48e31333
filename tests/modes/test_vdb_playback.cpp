// VDB scenes (docs/scene-format.md, "vdb"): what `sixway sim --vdb-out` exports plays back as the very
// volumes the simulation renders from, so every renderer draws the same images; the scene's transform turns,
// scales and moves a file exactly; frames repeat and empty frames are zero; bad files get one line.
#include <gmock/gmock.h>

#include <cstdio>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "io/error.h"
#include "io/vdb.h"
#include "modes/mode_renderer.h"
#include "modes/scene_source.h"
#include "reference/vdb_sequence.h"
#include "runtime/scene_volumes.h"
#include "scene/fluid_physics.h"
#include "scene/scene.h"
#include "sim/simulation.h"
#include "support/gpu_fixture.h"
#include "support/image_compare.h"
#include "support/temp_dir.h"

namespace sixway::test {
namespace {

namespace fs = std::filesystem;
const fs::path kVdb = SIXWAY_TEST_DATA_DIR "/vdb";
const fs::path kPlume = SIXWAY_TEST_DATA_DIR "/scenes/small_plume.json";
constexpr int kFrames = 3;

class VdbPlaybackTest : public GpuTest {
 protected:
  TempDir dir;
};

std::string inputErrorMessage(const std::function<void()>& f) {
  try {
    f();
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

std::vector<float> download(const gpu::Buffer* buffer) {
  return buffer->download<float>();
}

// The frames as `sixway sim --vdb-out` writes them: <name>_0001.vdb is the smoke after one frame.
void exportFrames(const gpu::Context& context, const gpu::PipelineCache& cache, const scene::Scene& scene,
                  const fs::path& out) {
  sim::Simulation simulation(context, cache, scene);
  for (int frame = 1; frame <= kFrames; ++frame) {
    simulation.advance(uint32_t(scene::lbmStepsPerFrame(scene)));
    auto [density, temperature] = simulation.smokeGrids();
    char name[64];
    std::snprintf(name, sizeof(name), "%s_%04d.vdb", scene.name.c_str(), frame);
    io::writeVdb(out / name, {{"density", &density}, {"temperature", &temperature}});
  }
}

// small_plume with its simulation replaced by the exported files, played back on the simulation's domain.
scene::Scene playbackScene(const fs::path& files, const scene::Grid& grid) {
  nlohmann::json j = nlohmann::json::parse(std::ifstream(kPlume));
  for (const char* key : {"grid", "fluid", "inlets", "obstacles"}) j.erase(key);
  j["time"].erase("steps_per_frame");
  const glm::vec3 max = grid.origin + glm::vec3(grid.size) * grid.cellSize;
  const glm::ivec3 cells = grid.size * grid.smokeUpres;
  j["vdb"] = {{"pattern", "small_plume_%04d.vdb"},
              {"first", 1},
              {"last", kFrames},
              {"temperature_grid", "temperature"},
              {"voxels", std::max({cells.x, cells.y, cells.z})},
              {"box_min", {grid.origin.x, grid.origin.y, grid.origin.z}},
              {"box_max", {max.x, max.y, max.z}}};
  return scene::parseScene(j, "playback.json", files);
}

TEST_F(VdbPlaybackTest, SimExportPlaysBackAsTheSameVolumesAndImages) {
  const scene::Scene simulated = scene::loadScene(kPlume);
  exportFrames(context(), pipelineCache(), simulated, dir.path());
  scene::Scene played = playbackScene(dir.path(), simulated.grid);
  auto playback = modes::openSceneVolumes(context(), pipelineCache(), played, kFrames, "playback.json");
  runtime::SimulatedVolumes live(context(), pipelineCache(), simulated, kFrames);

  scene::Scene renderScene = simulated;
  renderScene.obstacles.clear();  // the played-back scene has none to draw
  modes::ModeOptions options;
  options.mode = modes::RenderMode::Reference;
  modes::ModeRenderer fromSimulation(context(), pipelineCache(), renderScene, options);
  modes::ModeRenderer fromFiles(context(), pipelineCache(), played, options);
  for (int i = 0; i < kFrames; ++i) {
    const render::Volume a = live.volume(i), b = playback->volume(i);
    // On the simulation's own lattice, cell for cell.
    EXPECT_EQ(b.grid.size, a.grid.size);
    EXPECT_NEAR(b.grid.cellSize, a.grid.cellSize, 1e-7f);
    EXPECT_NEAR(glm::distance(b.grid.origin, a.grid.origin), 0.0f, 1e-6f);
    const std::vector<float> rhoA = download(a.density), rhoB = download(b.density);
    const std::vector<float> tA = download(a.temperature), tB = download(b.temperature);
    double worst = 0, mass = 0;
    for (std::size_t c = 0; c < rhoA.size(); ++c) {
      worst = std::max({worst, double(std::abs(rhoA[c] - rhoB[c])), double(std::abs(tA[c] - tB[c]))});
      mass += rhoB[c];
    }
    EXPECT_LT(worst, 2e-6) << "frame " << i;  // values up to 1e-6 are left out of the files
    EXPECT_GT(mass, 1.0) << "frame " << i;

    const double seconds = runtime::SimulatedVolumes::frameSeconds(simulated, i);
    const io::Image expected = fromSimulation.render(i, seconds, a).image;
    const io::Image actual = fromFiles.render(i, seconds, b).image;
    const ImageDifference d = compareImages(actual, expected);
    std::printf("frame %d: playback vs simulation %.2f dB, max-abs %.2g\n", i, d.psnr, d.maxAbs);
    EXPECT_TRUE(imagesMatch(actual, expected, {1e-3, 60.0}, "frame " + std::to_string(i)));
  }
}

scene::VdbSource source(std::vector<fs::path> files) {
  scene::VdbSource s;
  s.files = std::move(files);
  s.voxels = 24;
  return s;
}

TEST_F(VdbPlaybackTest, TheTransformTurnsScalesAndMovesTheFileExactly) {
  reference::VdbSequence upright(context(), source({kVdb / "smoke_000002.vdb"}));
  scene::VdbSource turned = source({kVdb / "smoke_000002.vdb"});
  turned.up = scene::VdbUp::Z;
  turned.scale = 0.5f;
  turned.translate = {1.0f, -2.0f, 3.0f};
  turned.densityScale = 2.0f;
  reference::VdbSequence blender(context(), turned);

  const render::VolumeGrid& a = upright.lattice();
  const render::VolumeGrid& b = blender.lattice();
  // (x, y, z) → (x, z, −y), then · 0.5 + t.
  EXPECT_EQ(b.size, glm::ivec3(a.size.x, a.size.z, a.size.y));
  EXPECT_NEAR(b.cellSize, 0.5f * a.cellSize, 1e-6f);
  const render::Box boxA = upright.bounds(), boxB = blender.bounds();
  EXPECT_NEAR(
      glm::distance(boxB.min, turned.translate + 0.5f * glm::vec3(boxA.min.x, boxA.min.z, -boxA.max.y)), 0.0f,
      0.5f * a.cellSize);
  const std::vector<float> rhoA = download(upright.volume(0).density);
  const std::vector<float> rhoB = download(blender.volume(0).density);
  double worst = 0, peak = 0;
  for (int k = 0; k < b.size.z; ++k)
    for (int j = 0; j < b.size.y; ++j)
      for (int i = 0; i < b.size.x; ++i) {
        // Cell (i, j, k) of the turned lattice is cell (i, n_y − 1 − k, j) of the upright one.
        const int ay = a.size.y - 1 - k, az = j;
        const float va = rhoA[(std::size_t(az) * a.size.y + ay) * a.size.x + i];
        const float vb = rhoB[(std::size_t(k) * b.size.y + j) * b.size.x + i];
        worst = std::max(worst, double(std::abs(vb - 2.0f * va)));
        peak = std::max(peak, double(va));
      }
  EXPECT_GT(peak, 0.1);
  EXPECT_LT(worst, 1e-4 * peak);
}

TEST_F(VdbPlaybackTest, FramesRepeatPerFileAndAnEmptyFrameIsZero) {
  scene::VdbSource s = source({kVdb / "smoke_000002.vdb", kVdb / "smoke_000001.vdb"});
  s.framesPerFile = 2;
  reference::VdbSequence sequence(context(), s);
  ASSERT_EQ(sequence.frameCount(), 4);
  EXPECT_EQ(sequence.frameName(1), "smoke_000002.vdb");
  EXPECT_EQ(sequence.frameName(2), "smoke_000001.vdb");
  const std::vector<float> first = download(sequence.volume(0).density);
  EXPECT_EQ(download(sequence.volume(1).density), first);
  double mass = 0;
  for (float v : first) mass += v;
  EXPECT_GT(mass, 1.0);
  for (float v : download(sequence.volume(2).density)) ASSERT_EQ(v, 0.0f) << "the empty frame keeps no smoke";
  EXPECT_FALSE(sequence.frame(3).has_value());
  const std::size_t notes = sequence.notes().size();
  sequence.volume(0);  // played again from the start, as the demo loops
  sequence.volume(2);
  EXPECT_EQ(sequence.notes().size(), notes) << "each note once";
  EXPECT_THAT(sequence.notes(), ::testing::Contains(::testing::HasSubstr("grid 'density' is empty")));
  EXPECT_THAT(sequence.notes(), ::testing::Contains(::testing::HasSubstr("non-uniform voxels")));
}

TEST_F(VdbPlaybackTest, BadFilesAndFrameCountsGetOneLine) {
  scene::VdbSource wrongName = source({kVdb / "smoke_000002.vdb"});
  wrongName.densityGrid = "smoke";
  EXPECT_THAT(inputErrorMessage([&] { reference::VdbSequence(context(), wrongName); }),
              ::testing::HasSubstr("smoke_000002.vdb: has no float grid 'smoke' (set vdb.density_grid"));
  // One file of a sequence without the density grid is an error, not an empty frame said only in a note.
  io::DenseGrid heat{.size = {4, 4, 4}, .values = std::vector<float>(64, 1.0f)};
  io::writeVdb(dir / "heat_only.vdb", {{"heat", &heat}});
  scene::VdbSource oneWithout = source({kVdb / "smoke_000002.vdb", dir / "heat_only.vdb"});
  EXPECT_THAT(inputErrorMessage([&] { reference::VdbSequence(context(), oneWithout); }),
              ::testing::HasSubstr("heat_only.vdb: has no float grid 'density'"));
  scene::VdbSource noHeat = source({kVdb / "smoke_000002.vdb"});
  noHeat.temperatureGrid = "heat";
  EXPECT_THAT(inputErrorMessage([&] { reference::VdbSequence(context(), noHeat); }),
              ::testing::HasSubstr("grid 'heat' (vdb.temperature_grid)"));
  scene::VdbSource allEmpty = source({kVdb / "smoke_000001.vdb"});
  EXPECT_THAT(inputErrorMessage([&] { reference::VdbSequence(context(), allEmpty); }),
              ::testing::HasSubstr("non-empty float grid 'density'"));

  scene::Scene scene = scene::loadScene(SIXWAY_TEST_DATA_DIR "/scenes/vdb_blender.json");
  EXPECT_THAT(
      inputErrorMessage([&] { modes::openSceneVolumes(context(), pipelineCache(), scene, 7, "v.json"); }),
      ::testing::HasSubstr("v.json: 7 frames asked for, but the vdb sequence has 6 (3 files"));
  EXPECT_THAT(inputErrorMessage([&] { sim::Simulation(context(), pipelineCache(), scene); }),
              ::testing::HasSubstr("there is nothing to simulate"));
}

// A VDB of 1e30 m voxels (or one scaled up past the scene's reach) made a lattice whose diagonal overflows a
// float: the renderers' light-grid loops never ended. The file is refused, named, before any allocation.
TEST_F(VdbPlaybackTest, GridsBeyondTheScenesReachGetOneLine) {
  io::DenseGrid huge{.size = {4, 4, 4}, .dx = glm::vec3(1e30f), .values = std::vector<float>(64, 1.0f)};
  io::writeVdb(dir / "huge_voxels.vdb", {{"density", &huge}});
  EXPECT_THAT(
      inputErrorMessage([&] { reference::VdbSequence(context(), source({dir / "huge_voxels.vdb"})); }),
      ::testing::MatchesRegex(
          ".*huge_voxels\\.vdb: grid 'density' reaches 4e\\+30 m from the origin \\(voxel "
          "size 1e\\+30 × vdb\\.scale 1\\), more than 1000000 m; .*"));
  scene::VdbSource scaled = source({kVdb / "smoke_000002.vdb"});
  scaled.scale = 1e6f;
  EXPECT_THAT(inputErrorMessage([&] { reference::VdbSequence(context(), scaled); }),
              ::testing::HasSubstr("smoke_000002.vdb: grid 'density' reaches"));
  // A box of the scene's own places the lattice: the file's voxel size then only samples it.
  scene::VdbSource boxed = source({dir / "huge_voxels.vdb"});
  boxed.box = std::pair(glm::vec3(0.0f), glm::vec3(1.0f));
  EXPECT_NO_THROW(reference::VdbSequence(context(), boxed));
}

// "voxels": "native" plays the file's own grid, cell for cell, inside one empty cell on every side: the
// smoke fades to zero over the voxel beyond the last active centre, as OpenVDB's trilinear sampler reads a
// grid's inactive background. The densest value bounds the sequence (the bake's light-grid spacing).
TEST_F(VdbPlaybackTest, NativeVoxelsAreTheFilesGridInsideAnEmptyBorder) {
  io::DenseGrid grid{.size = {5, 4, 3}, .origin = {0.3f, -0.2f, 1.0f}, .dx = glm::vec3(0.1f)};
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 5; ++i) grid.values.push_back(float(1 + i + 5 * j + 20 * k) / 60.0f);
  io::writeVdb(dir / "grid.vdb", {{"density", &grid}});
  scene::VdbSource native = source({dir / "grid.vdb"});
  native.voxels = scene::kNativeVoxels;
  reference::VdbSequence sequence(context(), native);
  const render::VolumeGrid& lattice = sequence.lattice();
  EXPECT_FLOAT_EQ(lattice.cellSize, 0.1f);
  EXPECT_EQ(lattice.size, glm::ivec3(7, 6, 5));
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(lattice.origin[a], grid.origin[a] - 0.1f, 1e-5f);
  const std::vector<float> density = download(sequence.volume(0).density);
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 7; ++i) {
        const bool inside = i >= 1 && i <= 5 && j >= 1 && j <= 4 && k >= 1 && k <= 3;
        const float expected = inside ? grid.at(i - 1, j - 1, k - 1) : 0.0f;
        ASSERT_NEAR(density[(std::size_t(k) * 6 + j) * 7 + i], expected, 1e-6f) << i << " " << j << " " << k;
      }
  EXPECT_FLOAT_EQ(sequence.densityBound(0, 1), 1.0f);
  // The bound is of the frames asked for.
  io::DenseGrid denser = grid;
  for (float& value : denser.values) value *= 2;
  io::writeVdb(dir / "denser.vdb", {{"density", &denser}});
  scene::VdbSource two = source({dir / "grid.vdb", dir / "denser.vdb"});
  two.voxels = scene::kNativeVoxels;
  reference::VdbSequence pair(context(), two);
  EXPECT_FLOAT_EQ(pair.densityBound(0, 1), 1.0f);
  EXPECT_FLOAT_EQ(pair.densityBound(1, 1), 2.0f);
  EXPECT_FLOAT_EQ(pair.densityBound(0, 2), 2.0f);

  // A count resamples, still inside a border: 10 cells along the active box's longest side (0.5 m).
  scene::VdbSource counted = source({dir / "grid.vdb"});
  counted.voxels = 10;
  EXPECT_FLOAT_EQ(reference::VdbSequence(context(), counted).lattice().cellSize, 0.05f);
  EXPECT_EQ(reference::VdbSequence(context(), counted).lattice().size, glm::ivec3(12, 10, 8));

  // Native cells need one cubic voxel size.
  scene::VdbSource uneven = source({kVdb / "densityAndHeat.vdb"});
  uneven.voxels = scene::kNativeVoxels;
  EXPECT_THAT(inputErrorMessage([&] { reference::VdbSequence(context(), uneven); }),
              ::testing::HasSubstr("densityAndHeat.vdb: grid 'density' has non-cubic voxels"));
}

}  // namespace
}  // namespace sixway::test
