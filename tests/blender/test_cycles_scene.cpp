// sixway's path-traced final image (`sixway render --mode pathtrace` of a scene playing the Mantaflow frame
// back) against Blender's Cycles rendering the scene (tools/blender/cycles_scene.py): a perspective camera, a
// directional light, a point light beside the smoke, uniform ambient light, coloured emission. Both sides
// render twice with independent seeds; the tolerances are on the noise-removed PSNR (cycles_agreement.h).
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "blender/blender_fixture.h"
#include "blender/cycles_agreement.h"

namespace sixway::test {
namespace {

namespace fs = std::filesystem;

class CyclesScene : public BlenderFixture {
 protected:
  // The scene: the Mantaflow frame (z up) on its own voxels, 64² pixels; `orders` scattering orders, with or
  // without emission, seed `seed`.
  fs::path scene(const std::string& name, bool emission, int seed) {
    nlohmann::json smoke = {{"extinction", 20}, {"albedo", 0.9}, {"phase_g", 0.2}};
    if (emission)
      smoke["emission"] = {{"intensity", 2},
                           {"ramp",
                            {{{"temperature", 0}, {"color", {0, 0, 0}}},
                             {{"temperature", 0.5}, {"color", {1, 0.35, 0.05}}},
                             {{"temperature", 1.5}, {"color", {1, 0.95, 0.8}}}}}};
    const nlohmann::json json = {
        {"name", name},
        {"vdb",
         {{"files", {vdbFrame().string()}},
          {"up", "z"},
          {"voxels", "native"},
          {"temperature_grid", "temperature"}}},
        {"smoke", smoke},
        {"camera", {{"position", {3.0, 1.6, 1.6}}, {"target", {1.0, 1.0, -1.0}}, {"fov_deg", 40}}},
        {"lights",
         {{{"type", "directional"},
           {"direction", {0.4, 1.0, 0.3}},
           {"color", {1.0, 0.95, 0.85}},
           {"intensity", 2.5}},
          {{"type", "point"},
           {"position", {2.1, 0.8, -0.6}},
           {"color", {1.0, 0.6, 0.3}},
           {"intensity", 0.6}}}},
        {"ambient", {{"color", {0.05, 0.06, 0.08}}}},
        {"render", {{"width", 64}, {"height", 64}, {"background", {0.02, 0.02, 0.03}}, {"seed", seed}}}};
    const fs::path path = dir_ / (name + ".json");
    std::ofstream(path) << json.dump(1);
    return path;
  }

  // sixway's path tracer and Cycles, each twice, `orders` orders; reported as `name`.
  Agreement agreement(const std::string& name, bool emission, int orders) {
    std::vector<Render> sixway, cycles;
    for (int seed : {1, 2}) {
      const std::string run_name = name + "_" + std::to_string(seed);
      const fs::path path = scene(run_name, emission, seed);
      const fs::path rendered = dir_ / (run_name + "_sixway");
      run(std::string(SIXWAY_EXE) + " render --scene '" + path.string() +
              "' --frames 1 --mode pathtrace --spp " + samples() + " --orders " + std::to_string(orders) +
              " --exr --validate --out '" + rendered.string() + "'",
          rendered.string() + ".log");
      const fs::path traced = dir_ / (run_name + "_cycles");
      run(blender("cycles_scene.py") + " --scene '" + path.string() + "' --out '" + traced.string() +
              "' --spp " + samples() + " --orders " + std::to_string(orders) + " --seed " +
              std::to_string(seed),
          traced.string() + ".log");
      if (HasFailure()) return {};
      sixway.push_back(readRenderedFrame(rendered / "frame_0000.exr"));
      cycles.push_back(readCyclesImage(traced));
    }
    const Agreement a = compareRenders(sixway, cycles, {0, 1, 2});
    report(name, {{"case", name},
                  {"samples_per_pixel", samples()},
                  {"masked_fraction", maskedFraction(cycles)},
                  {"rgb", a.json()}});
    EXPECT_GT(maskedFraction(cycles), 0.1);
    return a;
  }
};

// Every order, with emission.
TEST_F(CyclesScene, FinalImageAgrees) {
  const Agreement a = agreement("final_image", true, 64);
  ASSERT_FALSE(HasFailure());
  EXPECT_GE(a.biasPsnrLowerDb(), 40.0);
}

// Single scattering, no emission (with no volume bounces Cycles still scatters emission once,
// docs/blender.md).
TEST_F(CyclesScene, SingleScatteringFinalImageAgrees) {
  const Agreement a = agreement("final_image_single", false, 1);
  ASSERT_FALSE(HasFailure());
  EXPECT_GE(a.biasPsnrLowerDb(), 50.0);
}

// A simulated scene whose smoke wraps obstacles of three kinds (small_plume's sphere, a capsule moving across
// the plume, an icosahedron as a turned OBJ mesh; the key light held still): sixway's path tracer on the
// simulation's tenth frame against Cycles on that frame as `sixway sim --vdb-out` exports it (10 frames of 51
// lattice steps, by the scene's step rule; the smoke as VDB, the obstacles' triangles as OBJ), every order.
TEST_F(CyclesScene, ObstacleInTheSmokeAgrees) {
  nlohmann::json json = nlohmann::json::parse(std::ifstream(SIXWAY_TEST_DATA_DIR "/scenes/small_plume.json"));
  json["lights"][0].erase("path");
  json["obstacles"].push_back({{"type", "capsule"},
                               {"radius", 0.05},
                               {"height", 0.3},
                               {"axis", {0.0, 0.0, 1.0}},
                               {"motion",
                                {{"keyframes",
                                  {{{"time", 0.0}, {"position", {-0.3, 0.35, 0.0}}},
                                   {{"time", 2.0}, {"position", {0.3, 0.35, 0.0}}}}}}}});
  json["obstacles"].push_back({{"type", "mesh"},
                               {"file", SIXWAY_TEST_DATA_DIR "/meshes/icosahedron.obj"},
                               {"scale", 0.1},
                               {"rotate_deg", {20.0, 35.0, 0.0}},
                               {"translate", {-0.2, 0.95, -0.05}}});
  std::vector<Render> sixway, cycles;
  for (int seed : {1, 2}) {
    const std::string name = "obstacle_" + std::to_string(seed);
    json["render"]["seed"] = seed;
    const fs::path path = dir_ / (name + ".json");
    std::ofstream(path) << json.dump(1);
    const fs::path rendered = dir_ / (name + "_sixway"), exported = dir_ / (name + "_vdb");
    const fs::path traced = dir_ / (name + "_cycles");
    run(std::string(SIXWAY_EXE) + " render --scene '" + path.string() +
            "' --frames 1 --warmup 9 --mode pathtrace " + "--spp " + samples() + " --exr --validate --out '" +
            rendered.string() + "'",
        rendered.string() + ".log");
    run(std::string(SIXWAY_EXE) + " sim --scene '" + path.string() + "' --steps 510 --vdb-out '" +
            exported.string() + "'",
        exported.string() + ".log");
    run(blender("cycles_scene.py") + " --scene '" + path.string() + "' --vdb '" +
            (exported / "small_plume_0010.vdb").string() + "' --obstacles '" +
            (exported / "small_plume_0010.obj").string() + "' --out '" + traced.string() + "' --spp " +
            samples() + " --seed " + std::to_string(seed),
        traced.string() + ".log");
    ASSERT_FALSE(HasFailure());
    sixway.push_back(readRenderedFrame(rendered / "frame_0000.exr"));
    cycles.push_back(readCyclesImage(traced));
  }
  const Agreement a = compareRenders(sixway, cycles, {0, 1, 2});
  report("final_image_obstacle", {{"case", "final_image_obstacle"},
                                  {"samples_per_pixel", samples()},
                                  {"masked_fraction", maskedFraction(cycles)},
                                  {"rgb", a.json()}});
  EXPECT_GT(maskedFraction(cycles), 0.1);
  EXPECT_GE(a.biasPsnrLowerDb(), 40.0);

  // Without the triangles the script would draw other obstacles than sixway's: one line, no image.
  const fs::path bare = dir_ / "bare", log = dir_ / "bare.log";
  const int status =
      std::system((blender("cycles_scene.py") + " --scene '" + (dir_ / "obstacle_1.json").string() +
                   "' --vdb '" + (dir_ / "obstacle_1_vdb" / "small_plume_0010.vdb").string() + "' --out '" +
                   bare.string() + "' > '" + log.string() + "' 2>&1")
                      .c_str());
  EXPECT_NE(status, 0);
  std::ifstream in(log);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("obstacle_1.json: obstacles: give their triangles (--obstacles"), std::string::npos)
      << text;
  EXPECT_FALSE(fs::exists(bare));
}

}  // namespace
}  // namespace sixway::test
