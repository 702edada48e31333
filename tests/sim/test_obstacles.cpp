// shaders/sim/obstacles.comp and voxelize_mesh.comp (through sim::ObstacleSet) against CPU
// point-in-shape tests at the cell centres.
//
// Analytic shapes and inlets: every cell exactly (the scenes keep every cell centre more than 1e-3
// cells from a surface, far beyond the float rounding of the GPU's tests). Meshes are decided by an
// occupancy grid of half-cell voxels, so a cell centre within a voxel's half-diagonal (√3/4 cell) of the
// surface may go either way; cells farther away must match exactly, and the voxelized volume of the
// Stanford bunny must match the volume the mesh encloses within 3 % (the cells cut by the surface,
// about a third of the bunny's, each count whole or not at all; their errors mostly cancel).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numeric>

#include "cpu_shapes.h"
#include "cpu_simulation.h"
#include "gpu/buffer.h"
#include "gpu/sequence.h"
#include "gpu_state.h"
#include "io/obj.h"
#include "scene_fixtures.h"
#include "sim/flags_schedule.h"
#include "sim/obstacle_set.h"
#include "sim/simulation.h"
#include "support/gpu_fixture.h"
#include "support/temp_dir.h"

namespace sixway::test {
namespace {

using nlohmann::json;

constexpr glm::ivec3 kSize{24, 16, 12};
constexpr double kSurfaceMargin = 1e-3;
const double kVoxelHalfDiagonal = std::sqrt(3.0) / 4;  // cells

json sceneWith(const json& patch) {
  return latticeScene(kSize, 0.02, patch);
}

class ObstacleFlagsTest : public GpuTest {
 protected:
  // The flags buffer after marking the cells at each of `steps` in turn.
  std::vector<uint32_t> gpuFlags(const scene::Scene& scene, const std::vector<uint64_t>& steps) {
    const sim::ObstacleSet set(context(), pipelineCache(), scene, sim::latticeUnits(scene));
    gpu::Buffer params(context(), sizeof(sim::StepParams), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                       gpu::MemoryKind::HostUpload, "step parameters");
    gpu::Buffer dispatch(context(), sim::ObstacleSet::kFlagsDispatchStride,
                         VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, gpu::MemoryKind::HostUpload, "flags dispatch");
    const VkDispatchIndirectCommand groups = set.flagsGroups();
    std::memcpy(dispatch.mapped(), &groups, sizeof(groups));
    for (uint64_t step : steps) {
      auto* p = static_cast<sim::StepParams*>(params.mapped());
      std::memset(p, 0, sizeof(sim::StepParams));
      set.fill(*p, step);
      gpu::Sequence sequence(context());
      set.recordFlags(sequence, params, dispatch, 0);
      sequence.submit();
    }
    return set.flags().download<uint32_t>();
  }

  // Analytic shapes and inlets: the GPU flags after `steps` equal the CPU's, cell by cell.
  void expectFlagsMatch(const json& sceneJson, const std::vector<uint64_t>& steps) {
    const scene::Scene scene = parseLatticeScene(sceneJson);
    const CpuSimulation cpu(scene);
    std::vector<CellFlags> expected(size_t(kSize.x) * kSize.y * kSize.z);
    for (uint64_t step : steps) {
      ASSERT_GT(cpu.surfaceMargin(step), kSurfaceMargin)
          << "a cell centre lies on a surface at step " << step;
      expected = cpu.inputsAt(step, expected).flags;
    }
    const std::vector<uint32_t> got = gpuFlags(scene, steps);
    int mismatches = 0, solid = 0, inlet = 0, left = 0;
    for (size_t c = 0; c < got.size(); ++c) {
      solid += expected[c].solid();
      inlet += expected[c].inlet >= 0;
      left += expected[c].uncovered();
      if (got[c] == encodeFlags(expected[c])) continue;
      if (++mismatches <= 5)
        ADD_FAILURE() << "cell " << FieldError{0, int(c)}.where(kSize) << ": GPU flags 0x" << std::hex
                      << got[c] << ", CPU 0x" << encodeFlags(expected[c]);
    }
    EXPECT_EQ(mismatches, 0);
    EXPECT_GT(solid, 0);
    std::cout << "[ measured ] " << mismatches << " of " << got.size() << " cells differ (" << solid
              << " solid, " << inlet << " inlet, " << left << " left by an obstacle)\n";
  }
};

TEST_F(ObstacleFlagsTest, Sphere) {
  expectFlagsMatch(
      sceneWith({{"obstacles", {{{"type", "sphere"}, {"center", {9.3, 7.7, 5.9}}, {"radius", 4.23}}}}}), {0});
}

TEST_F(ObstacleFlagsTest, TiltedCylinder) {
  const json cylinder = {{"type", "cylinder"},
                         {"center", {12.2, 8.1, 6.3}},
                         {"radius", 2.6},
                         {"height", 9.0},
                         {"axis", {1.0, 2.0, 0.5}}};
  expectFlagsMatch(sceneWith({{"obstacles", {cylinder}}}), {0});
}

TEST_F(ObstacleFlagsTest, TiltedCapsule) {
  const json capsule = {{"type", "capsule"},
                        {"center", {12.2, 8.1, 6.3}},
                        {"radius", 2.6},
                        {"height", 10.7},
                        {"axis", {1.0, 2.0, 0.5}}};
  expectFlagsMatch(sceneWith({{"obstacles", {capsule}}}), {0});
}

TEST_F(ObstacleFlagsTest, Box) {
  const json box = {{"type", "box"}, {"center", {11.1, 7.35, 6.05}}, {"size", {9.3, 5.9, 6.7}}};
  expectFlagsMatch(sceneWith({{"obstacles", {box}}}), {0});
}

TEST_F(ObstacleFlagsTest, FirstObstacleWinsAndInletsOnlyInFluid) {
  // The box overlaps the sphere; the first inlet overlaps the sphere; the second is not on yet.
  const json scene =
      sceneWith({{"obstacles",
                  {{{"type", "sphere"}, {"center", {9.3, 7.7, 5.9}}, {"radius", 4.23}},
                   {{"type", "box"}, {"center", {13.1, 7.35, 6.05}}, {"size", {7.3, 5.9, 6.7}}}}},
                 {"inlets",
                  {{{"shape", "box"},
                    {"min", {2.0, 1.0, 2.0}},
                    {"max", {8.0, 6.0, 9.0}},
                    {"velocity", {0.0, 0.05, 0.0}}},
                   {{"shape", "disk"},
                    {"center", {19.0, 2.2, 6.0}},
                    {"radius", 2.3},
                    {"normal", {0.0, 1.0, 0.0}},
                    {"velocity", 0.05},
                    {"start", 3.0}},
                   {{"shape", "disk"},
                    {"center", {19.0, 12.2, 6.0}},
                    {"radius", 2.3},
                    {"normal", {1.0, 1.0, 0.0}},
                    {"velocity", 0.05}}}}});
  expectFlagsMatch(scene, {0});
}

TEST_F(ObstacleFlagsTest, MovingSphereRemembersTheCellsItLeft) {
  const json keyframes = {{{"time", -10.0}, {"position", {5.3, 8.7, 4.9}}},
                          {{"time", 90.0}, {"position", {15.3, 6.7, 7.9}}}};
  expectFlagsMatch(
      sceneWith(
          {{"obstacles", {{{"type", "sphere"}, {"radius", 4.2}, {"motion", {{"keyframes", keyframes}}}}}}}),
      {0, 7});
}

// The simulation computes the flags only when the geometry changed in the last two steps (FlagsSchedule):
// with a static sphere and an inlet that starts at 3 s (step 3), steps 0, 1, 3 and 4; after ten steps its
// flags are the ones a pass at every step gives.
TEST_F(ObstacleFlagsTest, SteadyGeometryIsMarkedOnlyAfterAChange) {
  const scene::Scene scene = parseLatticeScene(
      sceneWith({{"obstacles", {{{"type", "sphere"}, {"center", {9.3, 7.7, 5.9}}, {"radius", 4.23}}}},
                 {"inlets",
                  {{{"shape", "disk"},
                    {"center", {19.0, 2.2, 6.0}},
                    {"radius", 2.3},
                    {"normal", {0.0, 1.0, 0.0}},
                    {"velocity", 0.05},
                    {"start", 3.0}}}}}));
  sim::Simulation simulation(context(), pipelineCache(), scene);
  simulation.advance(10);
  EXPECT_EQ(simulation.flagPasses(), 4u);
  std::vector<uint64_t> every(10);
  std::iota(every.begin(), every.end(), 0);
  EXPECT_EQ(simulation.obstacles().flags().download<uint32_t>(), gpuFlags(scene, every));
}

TEST_F(ObstacleFlagsTest, AMovingObstacleIsMarkedEveryStep) {
  const json keyframes = {{{"time", 0.0}, {"position", {5.3, 8.7, 4.9}}},
                          {{"time", 90.0}, {"position", {15.3, 6.7, 7.9}}}};
  const scene::Scene scene = parseLatticeScene(sceneWith(
      {{"obstacles", {{{"type", "sphere"}, {"radius", 4.2}, {"motion", {{"keyframes", keyframes}}}}}}}));
  sim::Simulation simulation(context(), pipelineCache(), scene);
  simulation.advance(6);
  EXPECT_EQ(simulation.flagPasses(), 6u);
}

// The schedule itself: velocities and the inlets' smoke do not count as a change, a placement does.
TEST(FlagsScheduleTest, PassesFollowTheGeometry) {
  sim::FlagsSchedule schedule;
  sim::StepParams params{};
  params.counts = glm::uvec4(1, 1, 0, 0);
  params.obstacles[0].centre = glm::vec4(4, 5, 6, 0);
  params.inlets[0].smoke = glm::vec4(1, 0.5f, 1, 0);
  std::vector<bool> passes;
  for (int step = 0; step < 8; ++step) {
    params.counts.z = step;
    params.obstacles[0].velocity.x = 0.01f * step;
    params.inlets[0].velocity.y = 0.02f * step;
    params.inlets[0].smoke.x = 1.0f + step;
    if (step == 5) params.obstacles[0].centre.x += 0.5f;
    passes.push_back(schedule.needsPass(params));
  }
  EXPECT_EQ(passes, (std::vector<bool>{true, true, false, false, false, true, true, false}));
  EXPECT_EQ(schedule.passes(), 4u);
  EXPECT_EQ(schedule.steps(), 8u);
}

void writeText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

// The unit cube [0, 1]³ with outward-facing triangles.
const char* kCubeObj = R"(v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3
f 1 3 2
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 4 8 7
f 4 7 3
f 1 5 8
f 1 8 4
f 2 3 7
f 2 7 6
)";

// The corner tetrahedron of the unit cube, outward-facing.
const char* kTetraObj = R"(v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
)";

struct MeshComparison {
  int checked = 0, nearSurface = 0, mismatches = 0;
};

class MeshFlagsTest : public ObstacleFlagsTest {
 protected:
  // A mesh obstacle placed by `placement` (scale, translate, rotate_deg), its GPU flags, and the placed mesh.
  std::vector<uint32_t> meshFlags(const std::filesystem::path& file, const json& placement, glm::ivec3 size,
                                  WorldMesh& placed) {
    json mesh = {{"type", "mesh"}, {"file", file.string()}};
    mesh.merge_patch(placement);
    const scene::Scene scene = parseLatticeScene(latticeScene(size, 0.02, {{"obstacles", {mesh}}}));
    const auto& m = std::get<scene::MeshObstacle>(scene.obstacles[0].shape);
    placed = placeMesh(io::readObj(file), m.scale, glm::dvec3(m.translate), glm::dvec3(m.rotateDeg));
    return gpuFlags(scene, {0});
  }

  // A convex mesh: every cell farther than the voxel half-diagonal from the surface matches the CPU.
  MeshComparison compareConvex(const std::vector<uint32_t>& got, const WorldMesh& placed, glm::ivec3 size) {
    MeshComparison r;
    for (int c = 0; c < int(got.size()); ++c) {
      const ShapeTest t = convexMeshTest(glm::dvec3(cellOf(c, size)) + 0.5, placed);
      if (t.margin <= kVoxelHalfDiagonal) {
        ++r.nearSurface;
        continue;
      }
      ++r.checked;
      const uint32_t expected = t.inside ? 1u : 0u;
      if (got[c] != expected && ++r.mismatches <= 5)
        ADD_FAILURE() << FieldError{0, c}.where(size) << ": GPU flags 0x" << std::hex << got[c] << ", CPU 0x"
                      << expected << " (" << t.margin << " cells from the surface)";
    }
    std::cout << "[ measured ] " << r.mismatches << " of " << r.checked << " cells differ; " << r.nearSurface
              << " cells within the voxel half-diagonal not compared\n";
    return r;
  }
};

TEST_F(MeshFlagsTest, AxisAlignedCubeIsExact) {
  // Faces 0.1 cell off the cell faces: every cell centre is ≥ 0.4 and every occupancy-voxel centre ≥ 0.25
  // cell from the surface, so each cell is decided exactly (6 × 6 × 6 of them).
  TempDir dir;
  writeText(dir / "cube.obj", kCubeObj);
  WorldMesh placed;
  const std::vector<uint32_t> got =
      meshFlags(dir / "cube.obj", {{"scale", 6.0}, {"translate", {5.1, 4.1, 3.1}}}, kSize, placed);
  int inside = 0, mismatches = 0;
  for (int c = 0; c < int(got.size()); ++c) {
    const ShapeTest t = convexMeshTest(glm::dvec3(cellOf(c, kSize)) + 0.5, placed);
    ASSERT_GT(t.margin, 0.39);
    inside += t.inside;
    mismatches += got[c] != (t.inside ? 1u : 0u);
  }
  EXPECT_EQ(inside, 216);
  EXPECT_EQ(mismatches, 0);
}

TEST_F(MeshFlagsTest, RotatedTetrahedron) {
  TempDir dir;
  writeText(dir / "tetra.obj", kTetraObj);
  WorldMesh placed;
  const std::vector<uint32_t> got = meshFlags(
      dir / "tetra.obj",
      {{"scale", 13.0}, {"translate", {6.3, 3.2, 2.7}}, {"rotate_deg", {20.0, -35.0, 10.0}}}, kSize, placed);
  const MeshComparison r = compareConvex(got, placed, kSize);
  EXPECT_EQ(r.mismatches, 0);
  EXPECT_GT(r.checked, 0);
}

TEST_F(MeshFlagsTest, StanfordBunnyVolume) {
  // Scaled to 20 cells across (the model is 0.155 m wide), centred in the grid.
  const std::filesystem::path file = std::filesystem::path(SIXWAY_ASSETS_DIR) / "meshes/stanford-bunny.obj";
  const io::Mesh mesh = io::readObj(file);
  const double scale = 20.0 / (mesh.boundsMax.x - mesh.boundsMin.x);
  const glm::ivec3 size{26, 26, 22};
  const glm::dvec3 middle = 0.5 * glm::dvec3(mesh.boundsMin + mesh.boundsMax);
  const glm::dvec3 translate = 0.5 * glm::dvec3(size) - scale * middle;
  WorldMesh placed;
  const std::vector<uint32_t> got = meshFlags(
      file, {{"scale", scale}, {"translate", {translate.x, translate.y, translate.z}}}, size, placed);
  int cells = 0;
  for (uint32_t f : got) {
    ASSERT_TRUE(f == 0u || f == 1u) << "flags 0x" << std::hex << f;
    cells += f == 1u;
  }
  const double exact = enclosedVolume(placed);
  const double relativeError = std::abs(cells - exact) / exact;
  EXPECT_LT(relativeError, 0.03) << cells << " solid cells, the mesh encloses " << exact << " cells³";
  std::cout << "[ measured ] " << cells << " solid cells, enclosed volume " << exact
            << " cells³, relative error " << relativeError << "\n";
}

}  // namespace
}  // namespace sixway::test
