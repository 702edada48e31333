// sixway's six-way lightmaps (`sixway bake --vdb`) against Blender's Cycles rendering the same smoke, camera
// and lights (tools/blender/cycles_lightmaps.py; conventions: docs/blender.md, "The Cycles check") on a
// Mantaflow frame at native voxels. Each figure is also given with both sides' Monte Carlo noise taken out
// (cycles_agreement.h); the tolerances are on that figure.
#include <string>
#include <vector>

#include "blender/blender_fixture.h"
#include "blender/cycles_agreement.h"

namespace sixway::test {
namespace {

namespace fs = std::filesystem;

constexpr int kEmissive = 6;
const std::vector<int> kLightChannels = {0, 1, 2, 3, 4, 5};

class CyclesLightmaps : public BlenderFixture {
 protected:
  // One view of the frame, an oblique camera, 48² tiles.
  fs::path bake(const std::string& name, const std::string& options) {
    const fs::path out = dir_ / name;
    run(std::string(SIXWAY_EXE) + " bake --vdb '" + vdbFrame().string() + "' --out '" + out.string() +
            "' --tile 48 --voxels native --camera-position -5 -6 3 --camera-target 1 1 1 --camera-up 0 0 1 "
            "--validate " +
            options,
        dir_ / (name + ".log"));
    return out;
  }

  // Cycles rendering what `baked` baked, twice (seeds 1 and 2).
  std::vector<Render> cycles(const fs::path& baked) {
    std::vector<Render> renders;
    for (const char* seed : {"1", "2"}) {
      const std::string out = baked.string() + "_cycles" + seed;
      run(blender("cycles_lightmaps.py") + " --flipbook '" + (baked / "flipbook.json").string() +
              "' --out '" + out + "' --spp " + samples() + " --seed " + seed,
          out + ".log");
      renders.push_back(readCyclesLightmaps(out));
    }
    return renders;
  }

  struct Agreements {
    Agreement light, alpha, emissive;
  };

  // The bakes `baked` (one, or two with independent seeds) against `reference`, reported as `name`.
  Agreements agreement(const std::string& name, const std::vector<fs::path>& baked,
                       const std::vector<Render>& reference) {
    std::vector<Render> sixway;
    for (const fs::path& b : baked) sixway.push_back(readBakedFrame(b / "frames" / "frame_0000.exr"));
    const Agreements a{compareRenders(sixway, reference, kLightChannels), compareAlpha(sixway, reference),
                       compareRenders(sixway, reference, {kEmissive})};
    nlohmann::json perLight;
    const char* names[] = {"Right", "Left", "Top", "Bottom", "Back", "Front"};
    for (int c : kLightChannels) perLight[names[c]] = compareRenders(sixway, reference, {c}).json();
    report(name, {{"case", name},
                  {"samples_per_pixel", samples()},
                  {"masked_fraction", maskedFraction(reference)},
                  {"light", a.light.json()},
                  {"per_light", perLight},
                  {"alpha", a.alpha.json()},
                  {"emissive", a.emissive.json()}});
    return a;
  }
};

// Exact single scattering (the baker) with emission; the light grids' spacing chosen from the smoke (here
// 0.27 cells: the densest cell's optical depth is 1.85).
TEST_F(CyclesLightmaps, SingleScatteringAgrees) {
  const fs::path baked = bake("single", "--scattering single --emission 2");
  ASSERT_FALSE(HasFailure());
  const std::vector<Render> reference = cycles(baked);
  ASSERT_FALSE(HasFailure());
  EXPECT_GT(maskedFraction(reference), 0.2);
  const Agreements a = agreement("single", {baked}, reference);
  EXPECT_GE(a.light.biasPsnrLowerDb(), 50.0);
  EXPECT_GE(a.alpha.biasPsnrLowerDb(), 50.0);
  EXPECT_GE(a.emissive.biasPsnrLowerDb(), 50.0);
}

// Three times denser (optical depth 5.5 per cell): the light grids at their finest, a quarter cell.
TEST_F(CyclesLightmaps, DenseSmokeSingleScatteringAgrees) {
  const fs::path baked = bake("dense", "--scattering single --extinction 60");
  ASSERT_FALSE(HasFailure());
  const std::vector<Render> reference = cycles(baked);
  ASSERT_FALSE(HasFailure());
  const Agreements a = agreement("dense", {baked}, reference);
  EXPECT_GE(a.light.biasPsnrLowerDb(), 50.0);
  EXPECT_GE(a.alpha.biasPsnrLowerDb(), 50.0);
}

// Every order: the path tracer alone (--ms-all-orders) and the default bake (exact single scattering plus
// traced higher orders), each twice, against Cycles with 63 volume bounces; emission scattered too.
TEST_F(CyclesLightmaps, MultipleScatteringAgrees) {
  std::vector<fs::path> traced, split;
  for (const std::string seed : {"1", "2"}) {
    traced.push_back(
        bake("all_orders_" + seed, "--ms-all-orders --spp " + samples() + " --emission 2 --seed " + seed));
    split.push_back(bake("split_" + seed, "--emission 2 --seed " + seed));
  }
  ASSERT_FALSE(HasFailure());
  const std::vector<Render> reference = cycles(traced.front());
  ASSERT_FALSE(HasFailure());
  for (const auto& [name, baked] : {std::pair("all_orders", traced), std::pair("default_bake", split)}) {
    SCOPED_TRACE(name);
    const Agreements a = agreement(name, baked, reference);
    EXPECT_GE(a.light.biasPsnrLowerDb(), 40.0);
    EXPECT_GE(a.alpha.biasPsnrLowerDb(), 40.0);
    EXPECT_GE(a.emissive.biasPsnrLowerDb(), 40.0);
  }
}

}  // namespace
}  // namespace sixway::test
