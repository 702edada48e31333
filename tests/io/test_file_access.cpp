// io::AtomicFile, what every writer in io writes through: the file appears under its name only when complete,
// a write interrupted by an exception leaves nothing (and keeps an earlier file), and writers name the file
// when its directory is missing; the temporary files that killed processes leave are removed by the next
// writer of the same file, never a live process's.
#include "io/file_access.h"
#include "platform/platform.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

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

// A child process stopped by SIGKILL; reaped when `reap` is set, else left a zombie (its parent has not
// collected it, as a parent that killed it on a timeout may never do).
pid_t killedChild(bool reap) {
  const pid_t pid = fork();
  if (pid == 0) {
    pause();
    _exit(0);
  }
  kill(pid, SIGKILL);
  if (reap) {
    waitpid(pid, nullptr, 0);
  } else {
    siginfo_t info;
    waitid(P_PID, id_t(pid), &info, WEXITED | WNOWAIT);  // dead, but not collected
  }
  return pid;
}

std::string partialName(const std::string& name, long pid) {
  return "." + name + "." + std::to_string(pid) + ".partial";
}

TEST(AtomicFileTest, OnlyEndedProcessesHaveEnded) {
  EXPECT_FALSE(platform::processEnded(getpid()));
  const pid_t zombie = killedChild(false);
  EXPECT_TRUE(platform::processEnded(zombie));
  waitpid(zombie, nullptr, 0);
  EXPECT_TRUE(platform::processEnded(zombie));
}

TEST(AtomicFileTest, TheTemporaryFilesOfKilledRunsOfTheSameFileGo) {
  TempDir dir;
  const pid_t killed = killedChild(true);
  for (const std::string& name : {partialName("out.txt", killed), partialName("out.txt", getpid()),
                                  partialName("other.txt", killed), partialName("out.txt", 0) + "x"})
    std::ofstream(dir / name) << "half";
  io::removePartialsOfEndedRuns(dir / "out.txt");
  EXPECT_FALSE(fs::exists(dir / partialName("out.txt", killed)));
  EXPECT_TRUE(fs::exists(dir / partialName("out.txt", getpid())));  // a live process's: still being written
  EXPECT_TRUE(fs::exists(dir / partialName("other.txt", killed)));  // another file's: its writer's to remove
  EXPECT_EQ(entriesIn(dir.path()), 3);
}

TEST(AtomicFileTest, ANameWithRegexCharactersIsMatchedLiterally) {
  TempDir dir;
  const pid_t killed = killedChild(true);
  std::ofstream(dir / partialName("a+b (1).json", killed)) << "half";
  std::ofstream(dir / partialName("aab (1).json", killed)) << "half";
  io::removePartialsOfEndedRuns(dir / "a+b (1).json");
  EXPECT_FALSE(fs::exists(dir / partialName("a+b (1).json", killed)));
  EXPECT_TRUE(fs::exists(dir / partialName("aab (1).json", killed)));
}

}  // namespace
}  // namespace sixway::test
