// app::StagedDirectory, the output directories of render, sim and bake: files in an output folder (bake's
// frames/) are moved in and replaced like those at the top, and a directory that holds nothing but the
// staging directories of killed runs counts as absent.
#include "app/staged_directory.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

#include "support/input_error.h"
#include "support/temp_dir.h"

namespace sixway::test {
namespace {

namespace fs = std::filesystem;

bool isOutput(const std::string& name) {
  return name.starts_with("out") || name.starts_with("frames/f");
}
const app::StagedDirectory::OutputFolders kFolders{"frames"};

std::set<std::string> filesUnder(const fs::path& directory) {
  std::set<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(directory))
    names.insert(entry.path().lexically_relative(directory).string());
  return names;
}

std::string contentOf(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The staging directory of a run whose process has ended.
fs::path stagingOfAKilledRun(const fs::path& directory) {
  const pid_t child = fork();
  if (child == 0) _exit(0);
  waitpid(child, nullptr, 0);
  const fs::path staging = directory / (".render." + std::to_string(child) + ".partial");
  fs::create_directories(staging / "frames");
  std::ofstream(staging / "frame_0000.png") << "half";
  return staging;
}

TEST(StagedDirectoryTest, FilesOfAnOutputFolderAreMovedInAndReplaced) {
  TempDir dir;
  const fs::path out = dir / "out";
  fs::create_directories(out / "frames");
  for (const char* earlier : {"out_a", "out_b", "frames/f1", "frames/f2", "frames/notes.txt", "notes.txt"})
    std::ofstream(out / earlier) << "earlier";
  {
    app::StagedDirectory staged(out, "bake", true, isOutput, kFolders);
    std::ofstream(staged.stagedPath("out_a")) << "new";
    std::ofstream(staged.stagedPath("frames/f2")) << "new";
    std::ofstream(staged.stagedPath("frames/f3")) << "new";
    EXPECT_EQ(contentOf(out / "frames/f2"), "earlier");  // nothing changes before the commit
    staged.commit();
  }
  EXPECT_EQ(filesUnder(out), (std::set<std::string>{"out_a", "frames", "frames/f2", "frames/f3",
                                                    "frames/notes.txt", "notes.txt"}));
  EXPECT_EQ(contentOf(out / "frames/f2"), "new");
  EXPECT_EQ(contentOf(out / "frames/notes.txt"), "earlier");
}

TEST(StagedDirectoryTest, AnOutputFolderIsMadeWhenAbsent) {
  TempDir dir;
  {
    app::StagedDirectory staged(dir / "out", "bake", false, isOutput, kFolders);
    std::ofstream(staged.stagedPath("frames/f0")) << "new";
    staged.commit();
  }
  EXPECT_EQ(filesUnder(dir / "out"), (std::set<std::string>{"frames", "frames/f0"}));
}

TEST(StagedDirectoryTest, AFileWhereAnOutputFolderGoesIsRefusedBeforeAnyChange) {
  TempDir dir;
  const fs::path out = dir / "out";
  fs::create_directories(out);
  std::ofstream(out / "frames") << "a user's file";
  std::ofstream(out / "out_a") << "earlier";
  EXPECT_THAT(
      inputErrorMessage([&] { app::StagedDirectory::requireWritable(out, true, isOutput, kFolders); }),
      namesFileAndProblem(out / "frames", "is a regular file, not a directory; not replaced"));
  {
    app::StagedDirectory staged(out, "bake", true, isOutput, kFolders);
    std::ofstream(staged.stagedPath("out_a")) << "new";
    EXPECT_THAT(inputErrorMessage([&] { staged.commit(); }),
                namesFileAndProblem(out / "frames", "is a regular file, not a directory; not replaced"));
  }
  EXPECT_EQ(filesUnder(out), (std::set<std::string>{"frames", "out_a"}));
  EXPECT_EQ(contentOf(out / "out_a"), "earlier");
}

TEST(StagedDirectoryTest, AnUncommittedRunLeavesNothing) {
  TempDir dir;
  { app::StagedDirectory staged(dir / "out", "bake", false, isOutput, kFolders); }
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(StagedDirectoryTest, ADirectoryHoldingOnlyKilledRunsCountsAsAbsent) {
  TempDir dir;
  const fs::path out = dir / "out";
  stagingOfAKilledRun(out);
  stagingOfAKilledRun(out);
  app::StagedDirectory::requireWritable(out, false, isOutput);
  EXPECT_FALSE(fs::exists(out));
}

TEST(StagedDirectoryTest, ADirectoryWithMoreThanKilledRunsStays) {
  TempDir dir;
  const fs::path withFile = dir / "with_file", withLive = dir / "with_live", empty = dir / "empty";
  const fs::path killed = stagingOfAKilledRun(withFile);
  std::ofstream(withFile / "notes.txt") << "a user's file";
  stagingOfAKilledRun(withLive);
  fs::create_directories(withLive / (".render." + std::to_string(getpid()) + ".partial"));  // still running
  fs::create_directories(empty);
  for (const fs::path& out : {withFile, withLive, empty})
    EXPECT_THAT(inputErrorMessage([&] { app::StagedDirectory::requireWritable(out, false, isOutput); }),
                namesFileAndProblem(out, "exists already; pass --force"));
  EXPECT_TRUE(fs::exists(killed));
  EXPECT_EQ(filesUnder(withLive).size(), 4u);  // both staging directories stay
}

}  // namespace
}  // namespace sixway::test
