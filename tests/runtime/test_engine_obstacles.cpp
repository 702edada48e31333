// Obstacles from the engine (SmokeSimulation::setObstacles): a sphere, box, capsule or triangle mesh given by
// the engine before the first frame makes the same smoke and image, bit for bit, as the same obstacle in the
// scene file; given in a placed world, the same to float rounding. Changed mid-run, the lattice's solid cells
// follow each shape (cell centres inside it, by a CPU test of the shape; a mesh's as the scene file's), the
// renderer's meshes follow, and sixway submits and waits for nothing and the validation layer says nothing.
#include <gtest/gtest.h>
#include <sixway/device.h>
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/buffer.h"
#include "io/obj.h"
#include "runtime/engine_harness.h"
#include "runtime/scene_volumes.h"
#include "support/temp_dir.h"

namespace sixway::test {
namespace {

// small_plume with `obstacle` (a scene file's JSON) in place of its sphere.
std::filesystem::path sceneWith(const std::filesystem::path& dir, const nlohmann::json& obstacle) {
  std::ifstream in(kScene);
  nlohmann::json scene = nlohmann::json::parse(in);
  scene["obstacles"] = nlohmann::json::array({obstacle});
  const std::filesystem::path file = dir / (obstacle["type"].get<std::string>() + ".json");
  std::ofstream(file) << scene.dump();
  return file;
}

struct Shape {
  const char* name;
  nlohmann::json scene;  // in the scene file
  Obstacle engine;       // the same from the engine, in the scene's own coordinates
};

// A closed mesh's OBJ in `dir`, and its triangles as io::readObj reads them (which the engine's spans view).
struct ObjMesh {
  ObjMesh(const std::filesystem::path& dir, const std::string& name, const std::string& text)
      : file(dir / (name + ".obj")) {
    std::ofstream(file) << text;
    mesh = io::readObj(file);
    for (const glm::uvec3& t : mesh.triangles) indices.insert(indices.end(), {t.x, t.y, t.z});
  }
  std::filesystem::path file;
  io::Mesh mesh;
  std::vector<uint32_t> indices;
};

// |x| + |y| + |z| < 1, and a cube with the same bounds (|x|, |y|, |z| < 1).
ObjMesh octahedron(const std::filesystem::path& dir) {
  return ObjMesh(dir, "octahedron",
                 "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
                 "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n");
}
ObjMesh cube(const std::filesystem::path& dir) {
  return ObjMesh(dir, "cube",
                 "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                 "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 4 8 7\nf 4 7 3\n"
                 "f 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n");
}

std::vector<Shape> shapes(const ObjMesh& octahedron) {
  // The scene file's rotate_deg [10, 30, 0] as a matrix (scene::meshRotation's order: z, y, then x).
  glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(30.0f), glm::vec3(0, 1, 0));
  turn = glm::rotate(turn, glm::radians(10.0f), glm::vec3(1, 0, 0));
  return {{"mesh",
           {{"type", "mesh"},
            {"file", octahedron.file.string()},
            {"scale", 0.16},
            {"translate", {-0.02, 0.64, 0.04}},
            {"rotate_deg", {10.0, 30.0, 0.0}}},
           {.shape = Obstacle::Shape::Mesh,
            .position = {-0.02f, 0.64f, 0.04f},
            .vertices = octahedron.mesh.positions,
            .indices = octahedron.indices,
            .rotation = glm::mat3(turn),
            .scale = 0.16f}},
          {"sphere",
           {{"type", "sphere"}, {"center", {0.12, 0.7, 0.1}}, {"radius", 0.12}},
           {.shape = Obstacle::Shape::Sphere, .position = {0.12f, 0.7f, 0.1f}, .radius = 0.12f}},
          {"box",
           {{"type", "box"}, {"center", {-0.1, 0.62, 0.05}}, {"size", {0.2, 0.1, 0.26}}},
           {.shape = Obstacle::Shape::Box, .position = {-0.1f, 0.62f, 0.05f}, .size = {0.2f, 0.1f, 0.26f}}},
          {"capsule",
           {{"type", "capsule"},
            {"center", {0.05, 0.66, -0.02}},
            {"radius", 0.07},
            {"height", 0.36},
            {"axis", {1.0, 0.0, 0.0}}},
           {.shape = Obstacle::Shape::Capsule,
            .position = {0.05f, 0.66f, -0.02f},
            .radius = 0.07f,
            .height = 0.36f,
            .axis = {1.0f, 0.0f, 0.0f}}}};
}

struct Frames {
  std::vector<float> pixels, density;
};

// Four frames of `scene` into the engine's targets, with `obstacles` set before the first (if any), placed.
Frames fourFrames(BorrowingEngine& engine, const std::filesystem::path& scene, const glm::mat4& placement,
                  const std::vector<Obstacle>* obstacles) {
  EngineTargets targets(engine.context, 64, 64);
  SmokeSimulation simulation(engine.device, scene);
  simulation.setPlacement(placement);
  if (obstacles) {
    std::vector<Obstacle> world = *obstacles;
    for (Obstacle& o : world) {
      o.position = glm::vec3(placement * glm::vec4(o.position, 1.0f));
      o.axis = glm::vec3(placement * glm::vec4(o.axis, 0.0f));
      o.rotation = glm::mat3(placement) * o.rotation;
    }
    simulation.setObstacles(world, 0.0);
  }
  // The scene without obstacles has no shadow tiles of its own: both ask for one per light.
  SmokeRenderer renderer(engine.device, simulation, {.weights = kWeights, .shadowedLights = 2},
                         targets.target());
  Camera camera = sceneCamera();
  camera.position = glm::vec3(placement * glm::vec4(camera.position, 1.0f));
  camera.target = glm::vec3(placement * glm::vec4(camera.target, 1.0f));
  renderer.setCamera(camera);
  const float background[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  recordFrames(engine, targets, simulation, renderer, background, true, 4);
  return {targets.colorPixels(),
          runtime::Access::volumes(simulation).currentVolume().density->download<float>()};
}

TEST(EngineObstacles, AreTheScenesObstaclesWhenGivenTheSame) {
  TempDir dir;
  const std::filesystem::path bare = sceneWithoutObstacles(dir.path());
  Device own({.validate = true});
  BorrowingEngine engine(own);
  const glm::mat4 placement = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(3.0f, 0.0f, -2.0f)),
                                          glm::radians(30.0f), glm::vec3(0.0f, 1.0f, 0.0f));
  const Frames without = fourFrames(engine, bare, glm::mat4(1.0f), nullptr);
  const ObjMesh mesh = octahedron(dir.path());
  for (const Shape& shape : shapes(mesh)) {
    SCOPED_TRACE(shape.name);
    const std::filesystem::path file = sceneWith(dir.path(), shape.scene);
    const std::vector<Obstacle> engineObstacles{shape.engine};
    const Frames fromFile = fourFrames(engine, file, glm::mat4(1.0f), nullptr);
    const Frames fromEngine = fourFrames(engine, bare, glm::mat4(1.0f), &engineObstacles);
    EXPECT_EQ(maxDifference(fromEngine.density, fromFile.density), 0.0);
    EXPECT_EQ(maxDifference(fromEngine.pixels, fromFile.pixels), 0.0);
    EXPECT_GT(maxDifference(fromFile.density, without.density), 0.01) << "the obstacle changed nothing";
    // Placed (the shapes that turn with the placement): the world's positions come back into the scene with
    // float rounding (~1e-7 m).
    if (shape.engine.shape != Obstacle::Shape::Capsule && shape.engine.shape != Obstacle::Shape::Mesh)
      continue;
    const Frames placedFile = fourFrames(engine, file, placement, nullptr);
    const Frames placedEngine = fourFrames(engine, bare, placement, &engineObstacles);
    EXPECT_LT(maxDifference(placedEngine.density, placedFile.density), 1e-4);
    EXPECT_GT(psnr(placedEngine.pixels, placedFile.pixels), 60.0);
  }
  EXPECT_EQ(own.validationMessages(), 0u);
}

// The lattice cells an obstacle holds now: flags' low byte is its index + 1 (shaders/common/sim_grid.glsl).
std::vector<int> solidCells(const SmokeSimulation& simulation) {
  const sim::Simulation& sim = runtime::Access::volumes(simulation).simulation();
  std::vector<int> solid;
  for (uint32_t f : sim.obstacles().flags().download<uint32_t>()) solid.push_back(int(f & 0xffu));
  return solid;
}

// The cells whose centres lie inside each obstacle (scene = world here), first obstacle first; −1 where a
// mesh's surface passes within 0.3 cells (its voxels are half a cell: the lattice may go either way). Meshes
// are octahedra (6 vertices) or cubes (8).
std::vector<int> expectedCells(const std::vector<Obstacle>& obstacles) {
  std::ifstream in(kScene);
  const nlohmann::json scene = nlohmann::json::parse(in);
  const glm::ivec3 n(scene["grid"]["size"][0], scene["grid"]["size"][1], scene["grid"]["size"][2]);
  const float h = scene["grid"]["cell_size"];
  const glm::vec3 origin(scene["grid"]["origin"][0], scene["grid"]["origin"][1], scene["grid"]["origin"][2]);
  std::vector<int> cells(size_t(n.x) * n.y * n.z, 0);
  for (int z = 0; z < n.z; ++z)
    for (int y = 0; y < n.y; ++y)
      for (int x = 0; x < n.x; ++x) {
        const glm::vec3 p = origin + (glm::vec3(x, y, z) + 0.5f) * h;
        for (size_t o = 0; o < obstacles.size(); ++o) {
          const Obstacle& b = obstacles[o];
          const glm::vec3 d = p - b.position;
          bool inside = false;
          if (b.shape == Obstacle::Shape::Sphere) inside = glm::length(d) < b.radius;
          if (b.shape == Obstacle::Shape::Box) inside = glm::all(glm::lessThan(glm::abs(d), 0.5f * b.size));
          if (b.shape == Obstacle::Shape::Capsule) {
            const glm::vec3 axis = glm::normalize(b.axis);
            const float half = 0.5f * b.height - b.radius;
            const float t = glm::clamp(glm::dot(d, axis), -half, half);
            inside = glm::length(d - t * axis) < b.radius;
          }
          if (b.shape == Obstacle::Shape::Mesh) {
            const glm::vec3 q = glm::abs(glm::transpose(b.rotation) * d / b.scale);
            const bool cube = b.vertices.size() == 8;
            // 1 on the surface, and the distance to it in the mesh's units per unit of this measure.
            const float measure = cube ? std::max({q.x, q.y, q.z}) : q.x + q.y + q.z;
            const float perUnit = cube ? 1.0f : 1.0f / std::sqrt(3.0f);
            if (std::abs(1.0f - measure) * perUnit * b.scale < 0.3f * h) {
              cells[(size_t(z) * n.y + y) * n.x + x] = -1;
              break;
            }
            inside = measure < 1.0f;
          }
          if (inside) {
            cells[(size_t(z) * n.y + y) * n.x + x] = int(o) + 1;
            break;
          }
        }
      }
  return cells;
}

// Cells where the lattice and the CPU test disagree; none but cells within a hair of a surface should.
size_t disagreements(const std::vector<int>& lattice, const std::vector<int>& expected) {
  size_t count = 0;
  for (size_t i = 0; i < lattice.size(); ++i) count += expected[i] >= 0 && lattice[i] != expected[i];
  return count;
}

TEST(EngineObstacles, ChangeMidRunWithoutSubmissionsOrWaits) {
  TempDir dir;
  const std::filesystem::path scene = sceneWithoutObstacles(dir.path());
  Device own({.validate = true});
  EngineUploads uploads(runtime::Access::context(own));
  BorrowingEngine engine(own, uploads.submit());
  EngineTargets targets(engine.context, 64, 64);
  SmokeSimulation simulation(engine.device, scene);
  SmokeRenderer renderer(engine.device, simulation, {.weights = kWeights, .shadowedLights = 2},
                         targets.target());
  renderer.setCamera(sceneCamera());
  const float background[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  const ObjMesh octahedronMesh = octahedron(dir.path()), cubeMesh = cube(dir.path());
  const std::vector<Shape> all = shapes(octahedronMesh);
  const Obstacle mesh = all[0].engine, sphere = all[1].engine, box = all[2].engine, capsule = all[3].engine;
  Obstacle moved = sphere, meshMoved = mesh;
  moved.position += glm::vec3(-0.04f, 0.0f, 0.0f);
  meshMoved.position += glm::vec3(0.0f, 0.04f, 0.0f);
  // A mesh with the octahedron's bounds, pose and scale: only its voxels tell it apart.
  Obstacle sameBounds = meshMoved;
  sameBounds.vertices = cubeMesh.mesh.positions;
  sameBounds.indices = cubeMesh.indices;
  // Frame by frame: none; a sphere appears; it moves; it becomes a box; a capsule joins it; a mesh replaces
  // the box; the mesh moves, and rests; a cube takes its place; none.
  const std::vector<std::vector<Obstacle>> plan = {{},
                                                   {sphere},
                                                   {moved},
                                                   {box},
                                                   {box, capsule},
                                                   {mesh, capsule},
                                                   {meshMoved, capsule},
                                                   {meshMoved, capsule},
                                                   {meshMoved, capsule},
                                                   {sameBounds, capsule},
                                                   {}};
  const uint64_t kRestingAgain = 8;  // the third frame of the same mesh and capsule at the same places
  uint64_t passesBefore = 0;
  int sixwaysUploads = 0;  // after the first frame (the test's own downloads go through the engine too)
  for (uint64_t frame = 0; frame < plan.size(); ++frame) {
    SCOPED_TRACE("frame " + std::to_string(frame));
    const int uploadsBefore = uploads.calls;
    // 0.1 s is the scene's frame; the move takes 0.04 m in it, under the speed limit.
    simulation.setObstacles(plan[frame], 0.1);
    VkCommandBuffer commands = engine.begin();
    targets.recordClear(commands, background);
    simulation.record(commands, frame, 0.1);
    renderer.record(commands, frame);
    engine.submitAndWait();
    if (frame > 0) sixwaysUploads += uploads.calls - uploadsBefore;
    ASSERT_EQ(simulation.obstacleCount(), plan[frame].size());
    // Given again where they rest, the obstacles cost the lattice nothing: no cell is marked again.
    const uint64_t passes = runtime::Access::volumes(simulation).simulation().flagPasses();
    if (frame == kRestingAgain) {
      EXPECT_EQ(passes, passesBefore);
    }
    passesBefore = passes;
    // Every obstacle at rest at the frame's end is where the lattice's solid cells are (the moving sphere
    // arrives exactly then). Flags hold the last step's.
    const size_t wrong = disagreements(solidCells(simulation), expectedCells(plan[frame]));
    EXPECT_EQ(wrong, 0u);
    const render::ObstacleMeshes& meshes = runtime::Access::frame(renderer).meshes();
    EXPECT_EQ(meshes.empty(), plan[frame].empty()) << "the renderer's meshes did not follow";
  }
  EXPECT_EQ(sixwaysUploads, 0) << "sixway submitted one-time work for the obstacles";
  EXPECT_EQ(engine.device.hostWaits(), 0u);
  // Too many, not finite, a capsule shorter than its diameter, a negative time: refused by name.
  EXPECT_THROW(simulation.setObstacles(std::vector<Obstacle>(17, sphere), 0.1), std::invalid_argument);
  Obstacle bad = sphere;
  bad.position.x = NAN;
  EXPECT_THROW(simulation.setObstacles({bad}, 0.1), std::invalid_argument);
  bad = capsule;
  bad.height = 0.1f;
  try {
    simulation.setObstacles({bad}, 0.1);
    ADD_FAILURE() << "a capsule shorter than its diameter was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("obstacle 0: a capsule's height"), std::string::npos) << e.what();
  }
  EXPECT_THROW(simulation.setObstacles({sphere}, -1.0), std::invalid_argument);
  bad = mesh;
  bad.indices = bad.indices.subspan(0, 4);
  EXPECT_THROW(simulation.setObstacles({bad}, 0.1), std::invalid_argument);
  const std::vector<uint32_t> outOfRange = {0, 1, 6};
  bad.indices = outOfRange;
  EXPECT_THROW(simulation.setObstacles({bad}, 0.1), std::invalid_argument);
  bad = mesh;
  bad.rotation[0][0] = 2.0f;
  try {
    simulation.setObstacles({bad}, 0.1);
    ADD_FAILURE() << "a scaling rotation was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("obstacle 0: a mesh's rotation is not a rotation"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(simulation.obstacleCount(), 0u) << "a refused set changed the obstacles";
  EXPECT_EQ(own.validationMessages(), 0u);
}

// A new placement turns the instance under the engine's obstacles: given again at the same world places, they
// take the new scene-space pose (a capsule lying along world x lies along the scene's z after a quarter
// turn).
TEST(EngineObstacles, ANewPlacementTurnsThem) {
  TempDir dir;
  const std::filesystem::path scene = sceneWithoutObstacles(dir.path());
  Device own({.validate = true});
  BorrowingEngine engine(own);
  SmokeSimulation simulation(engine.device, scene);
  const Obstacle capsule = shapes(octahedron(dir.path()))[3].engine;
  uint64_t frame = 0;
  const auto step = [&] {
    simulation.setObstacles({capsule}, 0.1);
    simulation.record(engine.begin(), frame++, 0.1);
    engine.submitAndWait();
  };
  step();
  EXPECT_EQ(disagreements(solidCells(simulation), expectedCells({capsule})), 0u);
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(0, 1, 0));
  simulation.setPlacement(turn);
  step();
  Obstacle inScene = capsule;
  inScene.position = glm::vec3(glm::inverse(turn) * glm::vec4(capsule.position, 1.0f));
  inScene.axis = glm::vec3(glm::inverse(turn) * glm::vec4(capsule.axis, 0.0f));
  EXPECT_GT(std::abs(inScene.axis.z), 0.99f);
  EXPECT_EQ(disagreements(solidCells(simulation), expectedCells({inScene})), 0u);
  EXPECT_EQ(own.validationMessages(), 0u);
}

}  // namespace
}  // namespace sixway::test
