// tools/blender/sixway_flipbook.py, run headless on a Blender scene whose smoke domain has a baked OpenVDB
// cache (mantaflow_smoke.py --blend): it bakes the frames asked for with `sixway bake`, in the packing asked
// for, viewed as the scene camera sees them, and ends a missing cache frame with one line.
#include <gmock/gmock.h>

#include <fstream>
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

  // The add-on's headless run on the saved scene.
  std::string addOn(const std::string& options) {
    return "blender -b '" + (dir_ / "domain" / "scene.blend").string() + "' --python-exit-code 1 --python '" +
           (fs::path(SIXWAY_BLENDER_SCRIPTS) / "sixway_flipbook.py").string() + "' -- --sixway '" +
           SIXWAY_EXE + "' " + options;
  }
};

TEST_F(BlenderFlipbook, BakesTheDomainsCacheAsSixwayBakeDoes) {
  ASSERT_FALSE(HasFailure());
  const fs::path flipbook = dir_ / "flipbook";
  run(addOn("--out '" + flipbook.string() + "' --frames 5 8 --tile 32 --packing rlt-bbf --scattering single"),
      dir_ / "add_on.log");
  // The same bake by hand: the cache's files, the scene camera moved into their space (the domain's lower
  // corner at the origin).
  const fs::path data = dir_ / "domain" / "cache" / "data";
  const fs::path expected = dir_ / "expected";
  std::string files;
  for (int frame = 5; frame <= 8; ++frame)
    files += " '" + (data / ("fluid_data_000" + std::to_string(frame) + ".vdb")).string() + "'";
  run(std::string(SIXWAY_EXE) + " bake --vdb" + files + " --voxels native --tile 32 --packing rlt-bbf " +
          "--scattering single --camera-position 2.5 -3 2 --camera-target 1 1 1.2 --camera-up 0 0 1 --out '" +
          expected.string() + "'",
      dir_ / "expected.log");
  ASSERT_FALSE(HasFailure());

  const nlohmann::json sidecar = nlohmann::json::parse(std::ifstream(flipbook / "flipbook.json"));
  EXPECT_EQ(sidecar["layout"]["frames"], 4);
  for (const char* file :
       {"flipbook_RLT.tga", "flipbook_BBF.tga", "flipbook_RLT.tga.meta", "flipbook_BBF.png.meta"})
    EXPECT_TRUE(fs::exists(flipbook / file)) << file;
  for (int frame = 0; frame < 4; ++frame) {
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

}  // namespace
}  // namespace sixway::test
