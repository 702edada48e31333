// Inputs that are not regular files, or cannot be looked at: each is one line naming the path and what it is
// (a FIFO, a directory, a device; a path longer than the system allows), and none is opened, so a FIFO never
// blocks and a device is never read.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <climits>
#include <fstream>
#include <string>

#include "io/file_access.h"
#include "scene/scene.h"
#include "support/input_error.h"
#include "support/temp_dir.h"

namespace sixway::test {
namespace {

namespace fs = std::filesystem;

TEST(InputFileTest, SpecialFilesAreNamedForWhatTheyAre) {
  TempDir dir;
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0644), 0);
  fs::create_directory(dir / "folder");
  fs::create_symlink("/dev/zero", dir / "zero");  // followed by stat, never opened
  EXPECT_EQ(io::regularFileProblem(dir / "fifo"), "is a FIFO, not a regular file");
  EXPECT_EQ(io::regularFileProblem(dir / "folder"), "is a directory, not a regular file");
  EXPECT_EQ(io::regularFileProblem(dir / "zero"), "is a character device, not a regular file");
  EXPECT_EQ(io::regularFileProblem(dir / "absent", "no such weights file"), "no such weights file");
  EXPECT_THAT(inputErrorMessage([&] { io::readFileBytes(dir / "fifo"); }),
              namesFileAndProblem(dir / "fifo", "is a FIFO, not a regular file"));
  std::ofstream(dir / "file") << "{}";
  EXPECT_EQ(io::regularFileProblem(dir / "file"), "");
}

// std::filesystem::exists says false for such a path, which read as "no such file".
TEST(InputFileTest, APathLongerThanTheSystemAllowsIsSaidSo) {
  TempDir dir;
  std::ofstream(dir / "scene.json") << "{}";
  std::string dots;
  while (dots.size() < 5000) dots += "./";
  const fs::path longPath = dir / (dots + "scene.json");
  const std::string expected = "path is longer than the system allows (" +
                               std::to_string(longPath.native().size()) + " characters, at most " +
                               std::to_string(PATH_MAX - 1) + ")";
  EXPECT_EQ(io::regularFileProblem(longPath), expected);
  EXPECT_THAT(inputErrorMessage([&] { scene::loadScene(longPath); }),
              namesFileAndProblem(longPath, expected));

  const fs::path longName = dir / (std::string(300, 'a') + ".json");
  EXPECT_EQ(io::regularFileProblem(longName),
            "a name in the path is longer than the system allows (305 characters, at most " +
                std::to_string(NAME_MAX) + ")");
}

}  // namespace
}  // namespace sixway::test
