// JSON reports: written whole under a temporary name and renamed, so a write that fails midway leaves
// neither a truncated report nor the temporary file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "io/report.h"
#include "support/input_error.h"
#include "support/temp_dir.h"

namespace sixway::test {
namespace {

namespace fs = std::filesystem;

int entriesIn(const fs::path& directory) {
  return int(std::distance(fs::directory_iterator(directory), fs::directory_iterator()));
}

TEST(ReportTest, IsWrittenWhole) {
  TempDir dir;
  io::writeReport(dir / "r.json", {{"psnr", 30.5}});
  std::ifstream in(dir / "r.json");
  EXPECT_EQ(nlohmann::json::parse(in)["psnr"], 30.5);
  EXPECT_EQ(entriesIn(dir.path()), 1);
}

// A directory where the report's temporary file goes: its write fails after the report was encoded.
void blockTemporaryFile(const fs::path& report) {
  const fs::path temporary = report.parent_path() / ("." + report.filename().string() + "." +
                                                     std::to_string(::getpid()) + ".partial");
  fs::create_directories(temporary / "inside");  // not empty: the failed write's clean-up leaves it
}

TEST(ReportTest, AFailedWriteLeavesNoReport) {
  TempDir dir;
  blockTemporaryFile(dir / "r.json");
  EXPECT_THAT(inputErrorMessage([&] {
                io::writeReport(dir / "r.json", {{"run", 1}});
              }),
              namesFileAndProblem(dir / "r.json", "cannot write the file"));
  EXPECT_FALSE(fs::exists(dir / "r.json"));
  EXPECT_EQ(entriesIn(dir.path()), 1);  // the blocking directory alone
}

TEST(ReportTest, AFailedRewriteKeepsTheEarlierReport) {
  TempDir dir;
  io::writeReport(dir / "r.json", {{"run", 1}});
  blockTemporaryFile(dir / "r.json");
  EXPECT_THROW(io::writeReport(dir / "r.json", {{"run", 2}}), io::InputError);
  std::ifstream in(dir / "r.json");
  EXPECT_EQ(nlohmann::json::parse(in)["run"], 1);
}

// A path may hold any bytes; JSON holds UTF-8. The report is written, each invalid byte as U+FFFD.
TEST(ReportTest, StringsThatAreNotUtf8AreWrittenWithReplacementCharacters) {
  TempDir dir;
  io::writeReport(dir / "r.json", {{"out", std::string("/tmp/x\xff\xfey")}, {"frames", 2}});
  std::ifstream in(dir / "r.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["out"], "/tmp/x\uFFFD\uFFFDy");
  EXPECT_EQ(report["frames"], 2);
  EXPECT_EQ(entriesIn(dir.path()), 1);
}

TEST(ReportTest, ARewriteRemovesTheTemporaryFileOfAKilledWriter) {
  TempDir dir;
  const pid_t child = fork();
  if (child == 0) _exit(0);
  waitpid(child, nullptr, 0);
  const fs::path killed = dir / (".r.json." + std::to_string(child) + ".partial");
  std::ofstream(killed) << "{\"half";
  io::writeReport(dir / "r.json", {{"psnr", 30.5}});
  EXPECT_FALSE(fs::exists(killed));
  EXPECT_EQ(entriesIn(dir.path()), 1);
}

TEST(ReportTest, ExistingOutputsNeedForce) {
  TempDir dir;
  io::writeReport(dir / "r.json", {{"run", 1}});
  EXPECT_THAT(inputErrorMessage([&] { io::requireWritableFile(dir / "r.json", false); }),
              namesFileAndProblem(dir / "r.json", "exists already; pass --force"));
  EXPECT_NO_THROW(io::requireWritableFile(dir / "r.json", true));
  EXPECT_NO_THROW(io::requireWritableFile(dir / "absent.json", false));
}

TEST(ReportTest, SpecialFilesAreNeverOutputs) {
  TempDir dir;
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0644), 0);
  fs::create_directory(dir / "folder");
  io::writeReport(dir / "r.json", {{"run", 1}});
  for (bool force : {false, true}) {
    EXPECT_THAT(inputErrorMessage([&] { io::requireWritableFile(dir / "fifo", force); }),
                namesFileAndProblem(dir / "fifo", "is a FIFO, not a regular file"));
    EXPECT_THAT(inputErrorMessage([&] { io::requireWritableFile(dir / "folder", force); }),
                namesFileAndProblem(dir / "folder", "is a directory, not a regular file"));
    EXPECT_THAT(inputErrorMessage([&] { io::requireWritableDirectory(dir / "fifo", force); }),
                namesFileAndProblem(dir / "fifo", "is a FIFO, not a directory"));
    EXPECT_THAT(inputErrorMessage([&] { io::requireWritableDirectory(dir / "r.json", force); }),
                namesFileAndProblem(dir / "r.json", "is a regular file, not a directory"));
  }
  EXPECT_NO_THROW(io::requireWritableDirectory(dir / "folder", true));
}

TEST(ReportTest, AFileIsNeverRenamedOverAFifo) {
  TempDir dir;
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0644), 0);
  EXPECT_THAT(inputErrorMessage([&] {
                io::writeReport(dir / "fifo", {{"run", 1}});
              }),
              namesFileAndProblem(dir / "fifo", "is a FIFO, not a regular file; not replaced"));
  EXPECT_TRUE(fs::is_fifo(dir / "fifo"));
  EXPECT_EQ(entriesIn(dir.path()), 1);
}

TEST(ReportTest, AnOutputDirectoryIsClaimedOnce) {
  TempDir dir;
  EXPECT_TRUE(io::claimOutputDirectory(dir / "a" / "new", false));
  EXPECT_THAT(inputErrorMessage([&] { io::claimOutputDirectory(dir / "a" / "new", false); }),
              namesFileAndProblem(dir / "a" / "new", "exists already: another run made it"));
  EXPECT_FALSE(io::claimOutputDirectory(dir / "a" / "new", true));
  EXPECT_TRUE(io::claimOutputDirectory(dir / "b/", false));
}

}  // namespace
}  // namespace sixway::test
