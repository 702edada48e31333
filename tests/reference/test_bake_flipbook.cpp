// The traditional six-way bake from the real OpenVDB files: the sequence's lattice honours the files'
// transforms and non-uniform voxels, empty frames become transparent tiles, the flipbook and the per-frame
// EXRs agree, and the baked frame matches the CPU oracle on the resampled grid.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cpu_reference.h"
#include "image_stats.h"
#include "io/exr.h"
#include "io/vdb.h"
#include "reference/bake_flipbook.h"
#include "reference/flipbook.h"
#include "reference/vdb_sequence.h"
#include "render/billboard.h"
#include "support/input_error.h"
#include "support/temp_dir.h"
#include "test_volumes.h"

namespace sixway::test {
namespace {

const std::filesystem::path kVdb = SIXWAY_TEST_DATA_DIR "/vdb";

class BakeFlipbookTest : public RenderTest {
 protected:
  reference::FlipbookBake job(const render::VolumeSequence& sequence, int frames) {
    reference::FlipbookBake j;
    j.out = dir.path() / "bake";
    j.frameCount = frames;
    j.camera = render::framingCamera(sequence.bounds());
    j.smoke.extinction = 2.0f;
    j.settings.width = j.settings.height = 16;
    j.scattering = reference::Scattering::Single;  // the exact baker's tiles, compared with direct bakes
    return j;
  }
  reference::FlipbookBakeResult bake(render::VolumeSequence& sequence, const reference::FlipbookBake& j) {
    return reference::bakeFlipbook(context(), pipelineCache(), sequence, j,
                                   [this](const std::string& line) { lines.push_back(line); });
  }
  TempDir dir;
  std::vector<std::string> lines;
};

// densityAndHeat.vdb has voxels of 0.703 × 0.703 × 0.716: the lattice covers its world box with cubic cells,
// 24 along the longest side, and one empty cell beyond it on every side.
TEST_F(BakeFlipbookTest, LatticeCoversTheFilesWorldBoxWithCubicCells) {
  reference::VdbSequence sequence(context(), {kVdb / "densityAndHeat.vdb"}, 24, true);
  const io::VdbFile info = io::readVdbInfo(kVdb / "densityAndHeat.vdb");
  const render::Box box = sequence.bounds();
  const float cell = sequence.lattice().cellSize;
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const io::VdbGridInfo& grid : info.grids) {
    lo = glm::min(lo, grid.worldMin);
    hi = glm::max(hi, grid.worldMax);
  }
  EXPECT_NEAR(cell, std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) / 24, 1e-5f);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(box.min[a], lo[a] - cell, 1e-4f);
    EXPECT_GE(box.max[a], hi[a] + cell - 1e-4f);
    EXPECT_LT(box.max[a], hi[a] + 2 * cell);
  }
  EXPECT_EQ(std::max({sequence.lattice().size.x, sequence.lattice().size.y, sequence.lattice().size.z}),
            24 + 2);
}

// The bake of one frame is the exact baker applied to the resampled grid: compare with the CPU oracle run on
// the same lattice (read back from the file independently). This smoke is optically thick (σ_t · cell ≈ 2.3
// at the densest cells): the light grids' interpolation still stays within 2% of each channel's peak.
TEST_F(BakeFlipbookTest, FrameMatchesTheCpuOracleOnTheResampledGrid) {
  reference::VdbSequence sequence(context(), {kVdb / "densityAndHeat.vdb"}, 24, true);
  reference::FlipbookBake j = job(sequence, 1);
  j.smoke.emission.intensity = 1.0f;
  j.smoke.emission.ramp = {{0.0f, {0, 0, 0}}, {1.0f, {1.0f, 0.6f, 0.2f}}};
  const reference::FlipbookBakeResult result = bake(sequence, j);
  const io::Image baked = io::readExr(j.out / "frames" / "frame_0000.exr").image;

  const render::Box box = sequence.bounds();
  const auto grids = io::readVdbGrids(kVdb / "densityAndHeat.vdb", {"density", "heat"},
                                      io::ExplicitBounds{box.min, box.max, sequence.lattice().size});
  CpuVolume cpu{sequence.lattice(), grids.grids.at("density").values, grids.grids.at("heat").values};
  io::Image expected = bakeSixWay(cpu, j.smoke, j.camera, result.billboard, 16, 16, 0.5);
  // The EXR lists channels by name; put them in channel order.
  io::Image ordered(16, 16, expected.channels);
  for (int c = 0; c < 8; ++c) {
    const int from = *baked.channelIndex(expected.channels[c]);
    for (int i = 0; i < 256; ++i) ordered.pixels[i * 8 + c] = baked.pixels[i * 8 + from];
  }
  const auto errors = channelErrors(ordered, expected);
  for (int c = 0; c < 8; ++c) {
    EXPECT_GT(errors[c].maxRef, 0.01) << expected.channels[c];
    EXPECT_LT(errors[c].maxAbs, 0.02 * errors[c].maxRef) << expected.channels[c];
  }
}

// The flipbook's emissive component is Unity's Single Channel mask. Unity's formula (VFXLit.hlsl:
// multiplier · gradient(mask) · opacity, its gradient constant outside its keys) with the sidecar's settings
// gives the emission sixway shades from the premultiplied luminance of the per-frame EXR (SixWayShading's
// straight value: alpha · s · ramp gradient(e / (alpha · s)), black at 0 and proportional beyond the last
// key).
TEST_F(BakeFlipbookTest, UnitysEmissionOnTheMaskIsSixwaysEmission) {
  reference::VdbSequence sequence(context(), {kVdb / "densityAndHeat.vdb"}, 24, true);
  reference::FlipbookBake j = job(sequence, 1);
  j.smoke.emission.intensity = 3.0f;
  j.smoke.emission.ramp = {{0.0f, {0, 0, 0}}, {0.5f, {0.8f, 0.2f, 0.05f}}, {1.0f, {1.6f, 1.2f, 0.7f}}};
  const reference::FlipbookBakeResult result = bake(sequence, j);
  ASSERT_TRUE(result.emissiveMask);
  const nlohmann::json unity = nlohmann::json::parse(std::ifstream(result.sidecar))["emissive"]["unity"];
  const float multiplier = unity["emissive_multiplier"];
  std::vector<render::GradientKey> unityKeys;
  for (const nlohmann::json& key : unity["emissive_gradient"])
    unityKeys.push_back({key["position"], glm::vec3(key["color"][0], key["color"][1], key["color"][2])});
  const auto unityGradient = [&](float x) {
    if (x <= unityKeys.front().position) return unityKeys.front().color;
    for (std::size_t k = 1; k < unityKeys.size(); ++k)
      if (x <= unityKeys[k].position)
        return glm::mix(
            unityKeys[k - 1].color, unityKeys[k].color,
            (x - unityKeys[k - 1].position) / (unityKeys[k].position - unityKeys[k - 1].position));
    return unityKeys.back().color;
  };
  const std::vector<render::GradientKey> ramp = render::emissiveGradientFromRamp(j.smoke.emission);
  const auto sixwayGradient = [&](float x) {
    if (x <= ramp.front().position) return ramp.front().color * (x / ramp.front().position);
    for (std::size_t k = 1; k < ramp.size(); ++k)
      if (x <= ramp[k].position)
        return glm::mix(ramp[k - 1].color, ramp[k].color,
                        (x - ramp[k - 1].position) / (ramp[k].position - ramp[k - 1].position));
    return ramp.back().color * (x / ramp.back().position);
  };
  const float s = *render::emissiveStraightScale(j.smoke);
  const io::Image frame = io::readExr(j.out / "frames" / "frame_0000.exr").image;
  const io::Image a = io::readExr(j.out / "flipbook_A.exr").image,
                  b = io::readExr(j.out / "flipbook_B.exr").image;
  float brightest = 0.0f, worst = 0.0f;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const float alpha = frame.at(x, y, *frame.channelIndex("alpha"));
      const float e = frame.at(x, y, *frame.channelIndex("emissive"));
      const glm::vec3 sixway = alpha > 0.0f ? alpha * s * sixwayGradient(e / (alpha * s)) : glm::vec3(0.0f);
      const float opacity = a.at(x, y, *a.channelIndex("A")), mask = b.at(x, y, *b.channelIndex("A"));
      const glm::vec3 inUnity = multiplier * unityGradient(mask) * opacity;
      brightest = std::max(brightest, sixway.r);
      worst = std::max(worst, glm::length(inUnity - sixway));
    }
  EXPECT_GT(brightest, 0.1f) << "the smoke emits";
  EXPECT_LT(worst, 4e-3f * brightest) << "half-precision textures";
}

// All four third-party files as one sequence: Blender's first frame (every grid empty) is a transparent tile,
// the others are not; the flipbook reads back to the per-frame EXRs (half precision).
TEST_F(BakeFlipbookTest, RealVdbFilesBakeAndTheEmptyFrameIsTransparent) {
  reference::VdbSequence sequence(context(),
                                  {kVdb / "densityAndHeat.vdb", kVdb / "smoke_000001.vdb",
                                   kVdb / "smoke_000002.vdb", kVdb / "smoke_000003.vdb"},
                                  32, false);
  const reference::FlipbookBakeResult result = bake(sequence, job(sequence, 4));
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_THAT(lines[1], ::testing::HasSubstr("smoke_000001.vdb): empty"));
  EXPECT_THAT(sequence.notes(), ::testing::Contains(::testing::HasSubstr("grid 'density' is empty")));

  const reference::Flipbook book = reference::readFlipbook(result.sidecar);
  ASSERT_EQ(book.frames.size(), 4u);
  EXPECT_EQ(book.layout.columns, 2);
  // One light-grid spacing for the flipbook, from its densest cell.
  const nlohmann::json settings = nlohmann::json::parse(std::ifstream(result.sidecar))["provenance"]["bake"];
  const float tau = settings["light_grid_spacing_rule"]["densest_cell_optical_depth"];
  EXPECT_NEAR(tau, 2.0f * sequence.densityBound(0, 4) * sequence.cellSize(), 1e-5f);
  EXPECT_GT(sequence.densityBound(0, 4), 0.9f);
  EXPECT_FLOAT_EQ(settings["light_grid_spacing_cells"].get<float>(), reference::lightSpacingFor(tau));
  for (int f = 0; f < 4; ++f) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%04d.exr", f);
    const io::Image exr = io::readExr(dir.path() / "bake" / "frames" / name).image;
    double alpha = 0;
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) {
        for (int c = 0; c < 8; ++c) {
          const float v = exr.at(x, y, *exr.channelIndex(render::sixWayChannelNames()[c]));
          ASSERT_NEAR(book.frames[f].at(x, y, c), v, 1e-3f * (1 + v)) << f << " " << c;
        }
        alpha += book.frames[f].at(x, y, render::Alpha);
      }
    if (f == 1) {
      EXPECT_EQ(alpha, 0.0) << "the empty frame";
    } else {
      EXPECT_GT(alpha, 1.0) << name;
    }
  }
}

// Multiple scattering (the default of `sixway bake`) adds the higher orders to the six light channels;
// alpha and emission stay the exact ones. The sidecar says which scattering the flipbook holds.
TEST_F(BakeFlipbookTest, MultipleScatteringAddsToTheLightChannelsAndIsNamed) {
  reference::VdbSequence sequence(context(), {kVdb / "smoke_000002.vdb"}, 24, false);
  reference::FlipbookBake j = job(sequence, 1);
  const reference::Flipbook singleBook = reference::readFlipbook(bake(sequence, j).sidecar);
  EXPECT_EQ(singleBook.scattering, reference::Scattering::Single);
  const io::Image single = singleBook.frames.at(0);
  j.out = dir.path() / "multiple";
  j.scattering = reference::Scattering::Multiple;
  j.multiple.samples = 64;
  j.multiple.maxOrders = 32;
  j.multiple.seed = 5;
  const reference::Flipbook multipleBook = reference::readFlipbook(bake(sequence, j).sidecar);
  EXPECT_EQ(multipleBook.scattering, reference::Scattering::Multiple);
  const io::Image multiple = multipleBook.frames.at(0);
  double gain = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      EXPECT_EQ(multiple.at(x, y, render::Alpha), single.at(x, y, render::Alpha));
      EXPECT_EQ(multiple.at(x, y, render::Emissive), single.at(x, y, render::Emissive));
      for (int c = 0; c < render::kSixWayLights; ++c) gain += multiple.at(x, y, c) - single.at(x, y, c);
    }
  EXPECT_GT(gain, 0.5);
}

TEST_F(BakeFlipbookTest, FramesOutsideTheSequenceAndCamerasInsideTheBoxAreErrors) {
  reference::VdbSequence sequence(context(), {kVdb / "smoke_000002.vdb"}, 16, false);
  reference::FlipbookBake j = job(sequence, 2);
  EXPECT_THAT(inputErrorMessage([&] { bake(sequence, j); }),
              ::testing::HasSubstr("frames: 0..1 are outside"));
  j.frameCount = 1;
  j.camera = render::Camera::lookAt(sequence.bounds().centre(),
                                    sequence.bounds().centre() + glm::vec3(0, 0, -1), {0, 1, 0}, 40);
  EXPECT_THAT(inputErrorMessage([&] { bake(sequence, j); }), ::testing::HasSubstr("behind the camera"));
  EXPECT_THAT(
      inputErrorMessage([&] { reference::VdbSequence(context(), {kVdb / "missing.vdb"}, 16, false); }),
      ::testing::HasSubstr("missing.vdb: no such file"));
}

}  // namespace
}  // namespace sixway::test
