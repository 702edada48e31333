#include "io/obj.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>

#include "support/input_error.h"
#include "support/temp_dir.h"

namespace sixway::io {
namespace {

namespace fs = std::filesystem;
using test::inputErrorMessage;
using test::namesFileAndProblem;

constexpr const char* kCube = R"(# unit cube, six quads
mtllib cube.mtl
o cube
v -1 -1 -1
v  1 -1 -1
v  1  1 -1
v -1  1 -1
v -1 -1  1
v  1 -1  1
v  1  1  1
v -1  1  1
usemtl grey
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 4 8 7 3
f 1 5 8 4
f 2 3 7 6
)";

class ObjTest : public ::testing::Test {
 protected:
  fs::path write(const std::string& text) {
    std::ofstream(file) << text;
    return file;
  }
  std::string readError(const std::string& text) {
    write(text);
    return inputErrorMessage([&] { readObj(file); });
  }

  test::TempDir dir;
  fs::path file = dir / "mesh.obj";
};

TEST(ObjRead, StanfordBunny) {
  const Mesh bunny = readObj(fs::path(SIXWAY_ASSETS_DIR) / "meshes" / "stanford-bunny.obj");
  EXPECT_EQ(bunny.triangles.size(), 69451u);
  EXPECT_EQ(bunny.positions.size(), 35947u);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_TRUE(std::isfinite(bunny.boundsMin[axis]) && std::isfinite(bunny.boundsMax[axis]));
    EXPECT_LT(bunny.boundsMin[axis], bunny.boundsMax[axis]);
  }
  // The scanned bunny is about 16 cm long, feet near y = 0.03.
  EXPECT_NEAR(bunny.boundsMax.x - bunny.boundsMin.x, 0.156, 0.001);
  EXPECT_NEAR(bunny.boundsMin.y, 0.033, 0.001);
}

// Two objects written with normals read back as one mesh: the second's indices run on after the first's.
TEST_F(ObjTest, WrittenObjectsReadBack) {
  const ObjObject triangle{
      "a", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}}, {{0, 1, 2}}};
  const ObjObject lifted{
      "b", {{0, 0, 2}, {0.1f, 0, 2}, {0, 0.1f, 2}}, {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}}, {{0, 2, 1}}};
  writeObj(file, {triangle, lifted});
  const Mesh mesh = readObj(file);
  ASSERT_EQ(mesh.positions.size(), 6u);
  EXPECT_EQ(mesh.positions[4], glm::vec3(0.1f, 0, 2));
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.triangles[0], glm::uvec3(0, 1, 2));
  EXPECT_EQ(mesh.triangles[1], glm::uvec3(3, 5, 4));
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_THAT(text, ::testing::HasSubstr("o b\n"));
  EXPECT_THAT(text, ::testing::HasSubstr("f 4//4 6//6 5//5\n"));
}

TEST_F(ObjTest, WritingIntoAMissingDirectoryNamesTheFile) {
  const fs::path missing = dir / "none" / "mesh.obj";
  EXPECT_THAT(inputErrorMessage([&] { writeObj(missing, {}); }), ::testing::HasSubstr(missing.string()));
}

TEST_F(ObjTest, CubeQuadsBecomeTwelveTrianglesAndAMissingMaterialFileDoesNotMatter) {
  const Mesh cube = readObj(write(kCube));
  EXPECT_EQ(cube.positions.size(), 8u);
  EXPECT_EQ(cube.triangles.size(), 12u);
  EXPECT_EQ(cube.boundsMin, glm::vec3(-1.0f));
  EXPECT_EQ(cube.boundsMax, glm::vec3(1.0f));
}

TEST_F(ObjTest, WindowsLineEndings) {
  std::string text;
  for (const char c : std::string_view(kCube)) {
    if (c == '\n') text += '\r';
    text += c;
  }
  EXPECT_EQ(readObj(write(text)).triangles.size(), 12u);
}

TEST_F(ObjTest, MergesShapesAndResolvesRelativeIndices) {
  const Mesh mesh =
      readObj(write("o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
                    "o b\nv 0 0 2\nv 1 0 2\nv 0 1 2\nf -3 -2 -1\n"));
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.triangles[0], glm::uvec3(0, 1, 2));
  EXPECT_EQ(mesh.triangles[1], glm::uvec3(3, 4, 5));
  EXPECT_EQ(mesh.boundsMax, glm::vec3(1, 1, 2));
}

// Bad input: each case names the file and the problem.

TEST_F(ObjTest, MissingFile) {
  EXPECT_THAT(inputErrorMessage([&] { readObj(file); }), namesFileAndProblem(file, "no such file"));
}

TEST_F(ObjTest, EmptyFile) {
  EXPECT_THAT(readError(""), namesFileAndProblem(file, "no triangles"));
}

TEST_F(ObjTest, OnlyLinesAndPoints) {
  EXPECT_THAT(readError("v 0 0 0\nv 1 0 0\nl 1 2\np 1\n"), namesFileAndProblem(file, "no triangles"));
}

TEST_F(ObjTest, VertexWithTwoCoordinates) {
  EXPECT_THAT(readError("v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n"),
              namesFileAndProblem(file, "line 2: a vertex needs three numbers: 'v 1 0'"));
}

TEST_F(ObjTest, VertexWithAWordForACoordinate) {
  EXPECT_THAT(readError("v 0 0 0\nv 1 0 0\nv 0 one 0\nf 1 2 3\n"),
              namesFileAndProblem(file, "line 3: a vertex needs three numbers: 'v 0 one 0'"));
}

TEST_F(ObjTest, VertexCoordinatePastTheFloatRange) {
  EXPECT_THAT(readError("v 1e999 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
              namesFileAndProblem(file, "line 1: vertex coordinate '1e999' is not a finite float"));
}

TEST_F(ObjTest, TriangleIndexPastTheVertexCount) {
  EXPECT_THAT(
      readError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
      namesFileAndProblem(file, "a face refers to a vertex that does not exist (the file has 3 vertices)"));
}

TEST_F(ObjTest, QuadIndexPastTheVertexCount) {
  EXPECT_THAT(
      readError("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 5\n"),
      namesFileAndProblem(file, "a face refers to a vertex that does not exist (the file has 4 vertices)"));
}

TEST_F(ObjTest, RelativeIndexBeforeTheFirstVertex) {
  EXPECT_THAT(
      readError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n"),
      namesFileAndProblem(file, "a face refers to a vertex that does not exist (the file has 3 vertices)"));
}

TEST_F(ObjTest, ZeroIndex) {
  EXPECT_THAT(readError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"),
              namesFileAndProblem(file, "cannot parse OBJ"));
}

TEST_F(ObjTest, FaceWithTwoVertices) {
  EXPECT_THAT(readError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n"),
              namesFileAndProblem(file, "a face has fewer than 3 vertices"));
}

}  // namespace
}  // namespace sixway::io
