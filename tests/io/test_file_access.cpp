// io::AtomicFile, what every writer in io writes through: the file appears under its name only when complete,
// a write interrupted by an exception leaves nothing (and keeps an earlier file), and writers name the file
// when its directory is missing.
#include "io/file_access.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "io/png.h"
#include "support/input_error.h"
#include "support/temp_dir.h"

namespace sixway::test {
namespace {

namespace fs = std::filesystem;

int entriesIn(const fs::path& directory) {
  return int(std::distance(fs::directory_iterator(directory), fs::directory_iterator()));
}

std::string contentOf(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Writes half of the content, then fails the way a full disk or a killed encoder does: by throwing.
void interruptedWrite(const fs::path& target) {
  io::AtomicFile file(target);
  std::ofstream(file.temporaryPath()) << "half of the ";
  throw std::runtime_error("interrupted");
}

TEST(AtomicFileTest, TheFileAppearsOnlyOnCommit) {
  TempDir dir;
  io::AtomicFile file(dir / "out.txt");
  std::ofstream(file.temporaryPath()) << "whole";
  EXPECT_FALSE(fs::exists(dir / "out.txt"));
  file.commit();
  EXPECT_EQ(contentOf(dir / "out.txt"), "whole");
  EXPECT_EQ(entriesIn(dir.path()), 1);
}

TEST(AtomicFileTest, AnInterruptedWriteLeavesNoFile) {
  TempDir dir;
  EXPECT_THROW(interruptedWrite(dir / "out.txt"), std::runtime_error);
  EXPECT_EQ(entriesIn(dir.path()), 0);
}

TEST(AtomicFileTest, AnInterruptedRewriteKeepsTheEarlierFile) {
  TempDir dir;
  std::ofstream(dir / "out.txt") << "earlier";
  EXPECT_THROW(interruptedWrite(dir / "out.txt"), std::runtime_error);
  EXPECT_EQ(contentOf(dir / "out.txt"), "earlier");
  EXPECT_EQ(entriesIn(dir.path()), 1);
}

TEST(AtomicFileTest, AMissingDirectoryIsNamed) {
  TempDir dir;
  const fs::path target = dir / "no_such_dir" / "frame.png";
  EXPECT_THAT(inputErrorMessage([&] {
                io::writePng(target, io::Image(2, 2, {"R", "G", "B"}));
              }),
              namesFileAndProblem(target, "cannot write: directory"));
}

}  // namespace
}  // namespace sixway::test
