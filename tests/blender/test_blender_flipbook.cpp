// tools/blender/sixway_flipbook.py, run headless on a Blender scene whose smoke domain has a baked OpenVDB
// cache (mantaflow_smoke.py --blend): it bakes the frames asked for with `sixway bake`, in the packing asked
// for, viewed as the scene camera sees them, and ends a missing cache frame with one line.
#include <gmock/gmock.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include "blender/blender_fixture.h"
#include "io/exr.h"

namespace sixway::test {
namespace {

namespace fs = std::filesystem;

class BlenderFlipbook : public BlenderFixture {
 protected:
  void SetUp() override {
    run(blender("mantaflow_smoke.py") + " '" +
            (fs::path(SIXWAY_BLENDER_TEST_DIR) / "mantaflow_flipbook.json").string() + "' '" +
            (dir_ / "domain").string() + "' --blend",
        dir_ / "mantaflow.log");
  }

  // Frames `first`..`last` of the cache baked by hand with `camera` (position, target, up in the cache's
  // space), as the add-on's flipbook in `flipbook` must hold them: the same within float rounding of the
  // camera. `noise`: the domain "noisy" and its noise grid.
  void expectTheBakeByHand(const fs::path& flipbook, int first, int last, const std::string& camera,
                           bool noise = false) {
    const fs::path cache = dir_ / (noise ? "noisy" : "domain") / "cache" / (noise ? "noise" : "data");
    const fs::path expected = flipbook.string() + "_by_hand";
    std::string files;
    for (int frame = first; frame <= last; ++frame)
      files += " '" +
               (cache / ((noise ? "fluid_noise_000" : "fluid_data_000") + std::to_string(frame) + ".vdb"))
                   .string() +
               "'";
    run(std::string(SIXWAY_EXE) + " bake --vdb" + files + (noise ? " --density-grid density_noise" : "") +
            " --voxels native --tile 32 --packing rlt-bbf --scattering single " + camera + " --out '" +
            expected.string() + "'",
        expected.string() + ".log");
    ASSERT_FALSE(HasFailure());
    for (int frame = 0; frame <= last - first; ++frame) {
      const std::string name = "frames/frame_000" + std::to_string(frame) + ".exr";
      const io::Image got = io::readExr(flipbook / name).image, want = io::readExr(expected / name).image;
      ASSERT_EQ(got.pixels.size(), want.pixels.size());
      double worst = 0, peak = 0;
      for (std::size_t i = 0; i < got.pixels.size(); ++i) {
        worst = std::max(worst, double(std::abs(got.pixels[i] - want.pixels[i])));
        peak = std::max(peak, double(std::abs(want.pixels[i])));
      }
      EXPECT_GT(peak, 0.01) << name;
      EXPECT_LE(worst, 1e-4 * peak) << name;
    }
  }

  // The add-on's headless run on the saved scene (of `domain`).
  std::string addOn(const std::string& options, const std::string& domain = "domain") {
    return "blender -b --factory-startup '" + (dir_ / domain / "scene.blend").string() +
           "' --python-exit-code 1 --python '" +
           (fs::path(SIXWAY_BLENDER_SCRIPTS) / "sixway_flipbook.py").string() + "' -- --sixway '" +
           SIXWAY_EXE + "' " + options;
  }
};

// The domain is a unit cube scaled by its object (not applied) away from the origin: its cache's space starts
// at the lower corner (2, -2, 0), in metres.
TEST_F(BlenderFlipbook, BakesTheDomainsCacheAsSixwayBakeDoes) {
  ASSERT_FALSE(HasFailure());
  const fs::path flipbook = dir_ / "flipbook";
  run(addOn("--out '" + flipbook.string() + "' --frames 5 8 --tile 32 --packing rlt-bbf --scattering single"),
      dir_ / "add_on.log");
  ASSERT_FALSE(HasFailure());
  const nlohmann::json sidecar = nlohmann::json::parse(std::ifstream(flipbook / "flipbook.json"));
  EXPECT_EQ(sidecar["layout"]["frames"], 4);
  for (const char* file :
       {"flipbook_RLT.tga", "flipbook_BBF.tga", "flipbook_RLT.tga.meta", "flipbook_BBF.png.meta"})
    EXPECT_TRUE(fs::exists(flipbook / file)) << file;
  // The scene camera at (4.5, -5, 2) looking at (3, -1, 1.2), z up.
  expectTheBakeByHand(flipbook, 5, 8, "--camera-position 2.5 -3 2 --camera-target 1 1 1.2 --camera-up 0 0 1");

  // The front view: from -y at three times the domain's largest side (3 m) from its centre (3, -1, 1.5).
  const fs::path front = dir_ / "front";
  run(addOn("--out '" + front.string() + "' --frames 8 8 --tile 32 --packing rlt-bbf --scattering single " +
            "--camera front"),
      dir_ / "front.log");
  expectTheBakeByHand(front, 8, 8, "--camera-position 1 -8 1.5 --camera-target 1 -7 1.5 --camera-up 0 0 1");

  // A frame the cache does not hold is one line, and no flipbook.
  const fs::path missing = dir_ / "missing";
  const int status = std::system((addOn("--out '" + missing.string() + "' --frames 7 12") + " > '" +
                                  (dir_ / "missing.log").string() + "' 2>&1")
                                     .c_str());
  EXPECT_NE(status, 0);
  std::ifstream log(dir_ / "missing.log");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_THAT(text,
              ::testing::HasSubstr("fluid_data_0009.vdb: no such cache file (4 of frames 7..12 are missing"));
  EXPECT_FALSE(fs::exists(missing));
}

// Blender's noise: the add-on bakes the cache's finer grid (density_noise, half the voxel size at noise 2) as
// `sixway bake --density-grid density_noise` does; emission with noise is one line (the noise cache holds no
// temperature).
TEST_F(BlenderFlipbook, BakesTheNoiseGridOfADomainWithNoise) {
  ASSERT_FALSE(HasFailure());
  nlohmann::json config =
      nlohmann::json::parse(std::ifstream(fs::path(SIXWAY_BLENDER_TEST_DIR) / "mantaflow_flipbook.json"));
  config["noise"] = 2;
  std::ofstream(dir_ / "noisy.json") << config.dump(1);
  run(blender("mantaflow_smoke.py") + " '" + (dir_ / "noisy.json").string() + "' '" +
          (dir_ / "noisy").string() + "' --blend",
      dir_ / "noisy.log");
  ASSERT_FALSE(HasFailure());
  const fs::path flipbook = dir_ / "noisy_flipbook";
  run(addOn("--out '" + flipbook.string() + "' --frames 7 8 --tile 32 --packing rlt-bbf --scattering single",
            "noisy"),
      dir_ / "noisy_add_on.log");
  ASSERT_FALSE(HasFailure());
  const nlohmann::json sidecar = nlohmann::json::parse(std::ifstream(flipbook / "flipbook.json"));
  EXPECT_EQ(sidecar["provenance"]["source"]["density_grid"], "density_noise") << sidecar["provenance"].dump();
  expectTheBakeByHand(flipbook, 7, 8, "--camera-position 2.5 -3 2 --camera-target 1 1 1.2 --camera-up 0 0 1",
                      true);

  const int status = std::system((addOn("--out '" + (dir_ / "glow").string() + "' --emission 2", "noisy") +
                                  " > '" + (dir_ / "glow.log").string() + "' 2>&1")
                                     .c_str());
  EXPECT_NE(status, 0);
  std::ifstream log(dir_ / "glow.log");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_THAT(text, ::testing::HasSubstr("adds noise, whose cache holds no temperature to glow"));
  EXPECT_FALSE(fs::exists(dir_ / "glow"));
}

}  // namespace
}  // namespace sixway::test
