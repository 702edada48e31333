// src/platform/platform.h on this system (posix.cpp) and in standard C++ alone (portable.cpp, built here
// too so that it stays correct where it is used): files written and read whole, special files left unread,
// a process's id and end.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "platform/platform.h"

namespace sixway::test {
namespace {

// A fresh directory, removed with what it holds (this test links nothing of sixway but platform).
struct TempDir {
  TempDir()
      : root(std::filesystem::temp_directory_path() /
             ("sixway_platform_" + std::to_string(platform::processId()))) {
    std::filesystem::remove_all(root);
    std::filesystem::create_directories(root);
  }
  ~TempDir() { std::filesystem::remove_all(root); }
  const std::filesystem::path& path() const { return root; }
  std::filesystem::path root;
};

TEST(Platform, AFileWrittenIsReadWhole) {
  TempDir dir;
  const std::filesystem::path file = dir.path() / "cache.bin";
  const std::vector<uint8_t> bytes = {1, 2, 3, 0, 255, 7};
  EXPECT_EQ(platform::writeFile(file, bytes), "");
  const platform::FileRead read = platform::readRegularFile(file, 1 << 20);
  EXPECT_EQ(read.problem, "");
  EXPECT_EQ(std::vector<uint8_t>(read.bytes.begin(), read.bytes.end()), bytes);
  EXPECT_EQ(platform::writeFile(file, std::vector<uint8_t>{9}), "") << "truncated and rewritten";
  EXPECT_EQ(platform::readRegularFile(file, 1 << 20).bytes.size(), 1u);
}

TEST(Platform, WhatIsNotARegularFileOfTheSizeIsLeftUnread) {
  TempDir dir;
  const platform::FileRead missing = platform::readRegularFile(dir.path() / "none", 1 << 20);
  EXPECT_TRUE(missing.bytes.empty());
  EXPECT_EQ(missing.problem, "");
  EXPECT_EQ(platform::readRegularFile(dir.path(), 1 << 20).problem, "is a directory");
  const std::filesystem::path big = dir.path() / "big.bin";
  std::ofstream(big) << std::string(3u << 20, 'x');
  EXPECT_EQ(platform::readRegularFile(big, 2u << 20).problem, "holds 3 MiB, more than 2 MiB");
  EXPECT_NE(platform::writeFile(dir.path() / "no" / "such" / "dir", std::vector<uint8_t>{1}), "");
}

TEST(Platform, ThisProcessHasNotEnded) {
  EXPECT_EQ(platform::processId(), platform::processId());
  EXPECT_GT(platform::processId(), 0);
  EXPECT_FALSE(platform::processEnded(platform::processId()));
  EXPECT_FALSE(platform::processEnded(0));
}

}  // namespace
}  // namespace sixway::test
