#include "io/vdb.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <fstream>

#include "support/input_error.h"
#include "support/temp_dir.h"

namespace sixway::io {
namespace {

namespace fs = std::filesystem;
using test::inputErrorMessage;
using test::namesFileAndProblem;
using ::testing::ElementsAre;

const fs::path kVdbDir = fs::path(SIXWAY_TEST_DATA_DIR) / "vdb";
const fs::path kDensityAndHeat = kVdbDir / "densityAndHeat.vdb";
const fs::path kSmoke1 = kVdbDir / "smoke_000001.vdb";
const fs::path kSmoke2 = kVdbDir / "smoke_000002.vdb";
const fs::path kSmoke3 = kVdbDir / "smoke_000003.vdb";

float maxValue(const DenseGrid& grid) {
  return *std::max_element(grid.values.begin(), grid.values.end());
}

void expectNear(glm::vec3 actual, glm::vec3 expected, float tolerance) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// The voxel maximum and sum of a float grid, read with plain OpenVDB.
std::pair<float, double> maxAndSumWithOpenVdb(const fs::path& path, const std::string& name) {
  openvdb::initialize();
  openvdb::io::File file(path.string());
  file.open(false);
  const auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(name));
  float max = 0.0f;
  double sum = 0.0;
  for (auto value = grid->cbeginValueOn(); value; ++value) {
    max = std::max(max, *value);
    sum += *value;
  }
  return {max, sum};
}

double sum(const DenseGrid& grid) {
  double total = 0.0;
  for (float value : grid.values) total += value;
  return total;
}

TEST(VdbRead, DensityAndHeatListsTwoFloatGridsWithNonUniformVoxels) {
  const VdbFile file = readVdbInfo(kDensityAndHeat);
  ASSERT_EQ(file.grids.size(), 2u);
  const VdbGridInfo& density = file.grids[0];
  const VdbGridInfo& heat = file.grids[1];
  EXPECT_EQ(density.name, "density");
  EXPECT_EQ(heat.name, "heat");
  for (const VdbGridInfo& grid : file.grids) {
    EXPECT_EQ(grid.valueType, "float");
    EXPECT_EQ(grid.gridClass, "unknown");  // this file does not mark them as fog volumes
    EXPECT_FALSE(grid.empty);
    expectNear(grid.voxelSize, {0.703377f, 0.703377f, 0.716455f}, 1e-6f);
  }
  EXPECT_EQ(density.activeVoxelCount, 6124);
  EXPECT_EQ(heat.activeVoxelCount, 5224);
  EXPECT_EQ(density.indexMin, glm::ivec3(1, 1, 31));
  EXPECT_EQ(density.indexMax, glm::ivec3(23, 23, 72));
  // Voxel extents: translate + (index -+ 0.5) * voxel size.
  expectNear(density.worldMin, {-8.08883f, -8.08883f, -2.28303f}, 1e-4f);
  expectNear(density.worldMax, {8.08883f, 8.08883f, 27.8081f}, 1e-4f);
}

TEST(VdbRead, SamplingAtVoxelCentresReproducesTheVoxels) {
  // A lattice whose cells are the file's voxels: trilinear sampling then returns the voxel values.
  const VdbGridInfo density = readVdbInfo(kDensityAndHeat).grids[0];
  const ExplicitBounds voxels{density.worldMin, density.worldMax, density.indexMax - density.indexMin + 1};
  const auto [voxelMax, voxelSum] = maxAndSumWithOpenVdb(kDensityAndHeat, "density");
  const DenseGrid dense = readVdbDense(kDensityAndHeat, "density", voxels);
  EXPECT_EQ(dense.size, glm::ivec3(23, 23, 42));
  expectNear(dense.dx, density.voxelSize, 1e-5f);
  EXPECT_NEAR(maxValue(dense), voxelMax, 1e-5);
  EXPECT_NEAR(sum(dense), voxelSum, 1e-3);
  EXPECT_NEAR(voxelMax, 0.998f, 1e-3);
}

TEST(VdbRead, AutoBoundsResampleToCubicCellsOnOneLattice) {
  const VdbDenseGrids read = readVdbGrids(kDensityAndHeat, {"density", "heat"}, AutoBounds{64});
  EXPECT_TRUE(read.notes.empty());
  ASSERT_EQ(read.grids.size(), 2u);
  const DenseGrid& density = read.grids.at("density");
  const DenseGrid& heat = read.grids.at("heat");
  // The union of the active boxes is the density box (heat lies inside it); z is the longest axis.
  EXPECT_EQ(density.size.z, 64);
  EXPECT_EQ(density.dx.x, density.dx.y);
  EXPECT_EQ(density.dx.y, density.dx.z);
  expectNear(density.origin, {-8.08883f, -8.08883f, -2.28303f}, 1e-4f);
  EXPECT_EQ(heat.size, density.size);
  EXPECT_EQ(heat.origin, density.origin);
  // Cells (0.47) are finer than voxels (0.70), but trilinear sampling between voxel centres still lowers the
  // peaks (voxel maxima 0.9975 and 0.7595; sampled 0.980 and 0.747): allow 0.03 below.
  EXPECT_NEAR(maxValue(density), 0.998f, 0.03f);
  EXPECT_LE(maxValue(density), 0.9976f);
  EXPECT_NEAR(maxValue(heat), 0.760f, 0.03f);
  EXPECT_LE(maxValue(heat), 0.7596f);
}

TEST(VdbRead, FirstBlenderFrameHasNothingToReadButNotes) {
  const VdbFile info = readVdbInfo(kSmoke1);
  ASSERT_EQ(info.grids.size(), 4u);
  EXPECT_TRUE(
      std::all_of(info.grids.begin(), info.grids.end(), [](const VdbGridInfo& g) { return g.empty; }));
  std::vector<std::string> descriptions;
  for (const VdbGridInfo& grid : info.grids)
    descriptions.push_back(grid.name + " " + grid.valueType + " " + grid.gridClass);
  EXPECT_THAT(descriptions, ElementsAre("density float unknown", "shadow float unknown",
                                        "velocity vec3s staggered", "obstacles int32 unknown"));

  const VdbDenseGrids read = readVdbGrids(kSmoke1, {}, AutoBounds{32});
  EXPECT_TRUE(read.grids.empty());
  const std::string source = kSmoke1.string();
  EXPECT_THAT(read.notes, ElementsAre(source + ": grid 'density' is empty: skipped",
                                      source + ": grid 'shadow' is empty: skipped",
                                      source + ": grid 'velocity' is vec3s, not float: skipped",
                                      source + ": grid 'obstacles' is int32, not float: skipped"));
}

TEST(VdbRead, MissingOptionalGridIsANote) {
  const VdbDenseGrids read = readVdbGrids(kSmoke2, {"density", "temperature"}, AutoBounds{16});
  EXPECT_EQ(read.grids.size(), 1u);
  EXPECT_THAT(read.notes, ElementsAre(kSmoke2.string() + ": no grid 'temperature': skipped"));
}

TEST(VdbRead, BlenderFramesCountsAndBounds) {
  const VdbGridInfo smoke2 = readVdbInfo(kSmoke2).grids.at(0);
  EXPECT_EQ(smoke2.name, "density");
  EXPECT_EQ(smoke2.gridClass, "fog volume");
  EXPECT_EQ(smoke2.activeVoxelCount, 71983);
  EXPECT_EQ(smoke2.indexMin, glm::ivec3(1, 1, 11));
  EXPECT_EQ(smoke2.indexMax, glm::ivec3(51, 49, 90));
  expectNear(smoke2.voxelSize, {0.132601f, 0.132903f, 0.131697f}, 1e-6f);
  expectNear(smoke2.worldMin, {-3.38133f, -3.25614f, -1.25741f}, 1e-4f);
  expectNear(smoke2.worldMax, {3.38133f, 3.25614f, 9.27834f}, 1e-4f);

  const VdbGridInfo smoke3 = readVdbInfo(kSmoke3).grids.at(0);
  EXPECT_EQ(smoke3.activeVoxelCount, 90197);
  EXPECT_EQ(smoke3.indexMin, glm::ivec3(1, 1, 3));
  EXPECT_EQ(smoke3.indexMax, glm::ivec3(51, 49, 98));
}

// A sphere of density with a smooth edge and a temperature field, on cubic cells; dyadic sizes keep every
// position exact in float.
struct SphereScene {
  DenseGrid density, temperature;
  SphereScene() {
    density.size = {24, 20, 16};
    density.origin = {-0.75f, 0.125f, -0.5f};
    density.dx = glm::vec3(0.0625f);
    density.values.resize(24 * 20 * 16);
    temperature = density;
    const glm::vec3 centre = density.origin + glm::vec3(0.7f, 0.6f, 0.5f);
    for (int k = 0; k < 16; ++k) {
      for (int j = 0; j < 20; ++j) {
        for (int i = 0; i < 24; ++i) {
          const float r = glm::length(density.cellCentre(i, j, k) - centre);
          density.at(i, j, k) = std::clamp((0.4f - r) / 0.2f, 0.0f, 1.0f);
          temperature.at(i, j, k) = density.at(i, j, k) * density.at(i, j, k) * 0.8f;
        }
      }
    }
  }
};

// Two voxels a million voxels apart stretch the lattice to cells of 15625 voxels, whose centres miss both:
// the frame resamples to zeros, and says so.
TEST(VdbRead, SmokeBetweenTheSamplesGetsANote) {
  openvdb::initialize();
  test::TempDir dir;
  const fs::path file = dir / "two_far_voxels.vdb";
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->setTransform(openvdb::math::Transform::createLinearTransform(0.01));
  grid->tree().setValue(openvdb::Coord(0, 0, 0), 1.0f);
  grid->tree().setValue(openvdb::Coord(1'000'000, 0, 0), 1.0f);
  openvdb::io::File(file.string()).write({grid});

  const VdbDenseGrids read = readVdbGrids(file, {"density"}, AutoBounds{64});
  ASSERT_EQ(read.grids.count("density"), 1u);
  EXPECT_EQ(maxValue(read.grids.at("density")), 0.0f);
  const std::string expected =
      file.string() +
      ": grid 'density' holds nonzero voxels, but every sample of the 64×1×1 lattice "
      "falls between them (cells of 156.25";
  EXPECT_THAT(read.notes, ElementsAre(::testing::StartsWith(expected)));
  // Smoke that the samples reach gets no such note.
  EXPECT_TRUE(readVdbGrids(kSmoke2, {"density"}, AutoBounds{16}).notes.empty());
}

TEST(VdbWrite, RoundTripKeepsValuesAndBounds) {
  const SphereScene scene;
  test::TempDir dir;
  const fs::path file = dir / "sphere.vdb";
  writeVdb(file, {{"density", &scene.density}, {"temperature", &scene.temperature}});

  const DenseGrid& d = scene.density;
  const ExplicitBounds sameLattice{d.origin, d.origin + glm::vec3(d.size) * d.dx, d.size};
  const VdbDenseGrids read = readVdbGrids(file, {"density", "temperature"}, sameLattice);
  ASSERT_EQ(read.grids.size(), 2u);
  for (const auto& [name, written] :
       {std::pair{"density", &scene.density}, {"temperature", &scene.temperature}}) {
    const DenseGrid& back = read.grids.at(name);
    ASSERT_EQ(back.values.size(), written->values.size());
    for (std::size_t i = 0; i < back.values.size(); ++i) {
      ASSERT_NEAR(back.values[i], written->values[i], 1e-6f) << name << " cell " << i;
    }
  }

  // The world box of the active voxels is the box of the non-zero cells.
  glm::ivec3 lo(INT32_MAX), hi(INT32_MIN);
  for (int k = 0; k < d.size.z; ++k) {
    for (int j = 0; j < d.size.y; ++j) {
      for (int i = 0; i < d.size.x; ++i) {
        if (d.at(i, j, k) > 1e-6f) {
          lo = glm::min(lo, glm::ivec3(i, j, k));
          hi = glm::max(hi, glm::ivec3(i, j, k));
        }
      }
    }
  }
  const VdbGridInfo info = readVdbInfo(file).grids.at(0);
  expectNear(info.worldMin, d.origin + glm::vec3(lo) * d.dx, 1e-6f);
  expectNear(info.worldMax, d.origin + glm::vec3(hi + 1) * d.dx, 1e-6f);
}

TEST(VdbWrite, PlainOpenVdbReadsWhatWeWrite) {
  const SphereScene scene;
  test::TempDir dir;
  const fs::path file = dir / "sphere.vdb";
  writeVdb(file, {{"density", &scene.density}, {"temperature", &scene.temperature}});

  openvdb::initialize();
  openvdb::io::File vdb(file.string());
  vdb.open();
  const openvdb::GridPtrVecPtr grids = vdb.getGrids();
  ASSERT_EQ(grids->size(), 2u);
  EXPECT_EQ((*grids)[0]->getName(), "density");
  EXPECT_EQ((*grids)[1]->getName(), "temperature");
  for (const auto& grid : *grids) {
    EXPECT_EQ(grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
    EXPECT_EQ(grid->valueType(), "float");
    EXPECT_EQ(grid->voxelSize(), openvdb::Vec3d(0.0625));
  }
  // Voxel (i, j, k) is cell (i, j, k), centred at origin + (i + 0.5) * dx.
  const auto density = openvdb::gridPtrCast<openvdb::FloatGrid>((*grids)[0]);
  const glm::vec3 centre = scene.density.cellCentre(12, 9, 8);
  EXPECT_EQ(density->transform().worldToIndexCellCentered(openvdb::Vec3d(centre.x, centre.y, centre.z)),
            openvdb::Coord(12, 9, 8));
  EXPECT_EQ(density->tree().getValue(openvdb::Coord(12, 9, 8)), scene.density.at(12, 9, 8));
  EXPECT_FALSE(density->tree().isValueOn(openvdb::Coord(0, 0, 0))) << "zero cells are inactive background";
}

// Bad input: each case names the file and the problem.

TEST(VdbBadInput, MissingFile) {
  const fs::path file = kVdbDir / "no_such.vdb";
  EXPECT_THAT(inputErrorMessage([&] { readVdbInfo(file); }), namesFileAndProblem(file, "no such file"));
}

TEST(VdbBadInput, TextFileNamedVdb) {
  test::TempDir dir;
  const fs::path file = dir / "smoke.vdb";
  std::ofstream(file) << "density = 1.0\n";
  EXPECT_THAT(inputErrorMessage([&] { readVdbInfo(file); }), namesFileAndProblem(file, "not a VDB file"));
}

TEST(VdbBadInput, TruncatedRealFile) {
  // OpenVDB's own file reader crashes on this one.
  test::TempDir dir;
  const fs::path file = dir / "smoke_000002.vdb";
  fs::copy_file(kSmoke2, file);
  fs::resize_file(file, fs::file_size(file) / 2);
  EXPECT_THAT(inputErrorMessage([&] { readVdbInfo(file); }), namesFileAndProblem(file, "truncated VDB file"));
}

TEST(VdbBadInput, MissingGridName) {
  EXPECT_THAT(inputErrorMessage([&] { readVdbDense(kDensityAndHeat, "temperature", AutoBounds{8}); }),
              namesFileAndProblem(kDensityAndHeat, "no grid 'temperature' (the file has: density, heat)"));
}

TEST(VdbBadInput, NonFloatGridByName) {
  EXPECT_THAT(inputErrorMessage([&] { readVdbDense(kSmoke1, "obstacles", AutoBounds{8}); }),
              namesFileAndProblem(kSmoke1, "grid 'obstacles' is int32, not float"));
}

TEST(VdbBadInput, EmptyGridHasNoBoundsToTake) {
  EXPECT_THAT(inputErrorMessage([&] { readVdbDense(kSmoke1, "density", AutoBounds{8}); }),
              namesFileAndProblem(kSmoke1, "grid 'density' is empty"));
}

TEST(VdbBadInput, WriteCellsThatAreNotCubic) {
  SphereScene scene;
  scene.density.dx.z = 0.07f;
  test::TempDir dir;
  const fs::path file = dir / "sphere.vdb";
  EXPECT_THAT(
      inputErrorMessage([&] {
        writeVdb(file, {{"density", &scene.density}});
      }),
      namesFileAndProblem(file, "grid 'density': cell size (0.062500, 0.062500, 0.070000) is not cubic"));
  EXPECT_FALSE(fs::exists(file));
}

TEST(VdbBadInput, WriteIntoAMissingDirectory) {
  const SphereScene scene;
  test::TempDir dir;
  const fs::path file = dir / "missing" / "sphere.vdb";
  EXPECT_THAT(inputErrorMessage([&] {
                writeVdb(file, {{"density", &scene.density}});
              }),
              namesFileAndProblem(file, "does not exist"));
}

}  // namespace
}  // namespace sixway::io
