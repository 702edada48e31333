// JSON reports: written whole under a temporary name and renamed, so a write that fails midway leaves
// neither a truncated report nor the temporary file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

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

TEST(ReportTest, AWriteThatThrowsMidwayLeavesNoFile) {
  TempDir dir;
  // Not UTF-8: nlohmann throws while the report is being written, after its temporary file is open.
  const nlohmann::json bad = {{"name", std::string("\xff\xfe")}};
  EXPECT_THAT(inputErrorMessage([&] { io::writeReport(dir / "r.json", bad); }),
              namesFileAndProblem(dir / "r.json", "cannot write the report"));
  EXPECT_EQ(entriesIn(dir.path()), 0);
}

TEST(ReportTest, AFailedRewriteKeepsTheEarlierReport) {
  TempDir dir;
  io::writeReport(dir / "r.json", {{"run", 1}});
  EXPECT_THROW(io::writeReport(dir / "r.json", {{"name", std::string("\xff")}}), io::InputError);
  std::ifstream in(dir / "r.json");
  EXPECT_EQ(nlohmann::json::parse(in)["run"], 1);
  EXPECT_EQ(entriesIn(dir.path()), 1);
}

TEST(ReportTest, ExistingOutputsNeedForce) {
  TempDir dir;
  io::writeReport(dir / "r.json", {{"run", 1}});
  EXPECT_THAT(inputErrorMessage([&] { io::requireWritable(dir / "r.json", false); }),
              namesFileAndProblem(dir / "r.json", "exists already; pass --force"));
  EXPECT_NO_THROW(io::requireWritable(dir / "r.json", true));
  EXPECT_NO_THROW(io::requireWritable(dir / "absent.json", false));
}

}  // namespace
}  // namespace sixway::test
