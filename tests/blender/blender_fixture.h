#pragma once
// What the tests that run Blender share: the Mantaflow frame they render (tools/blender/mantaflow_smoke.py on
// mantaflow_fire.json), commands run with their output kept in a log, the sample count and the reports.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "support/temp_dir.h"

namespace sixway::test {

class BlenderFixture : public ::testing::Test {
 protected:
  // Makes the Mantaflow sequence.
  void SetUp() override;

  // Runs `command` with its output in `log`; a failure names the command and shows the log's tail.
  void run(const std::string& command, const std::filesystem::path& log);
  // `blender -b --factory-startup --python tools/blender/<script> --`
  static std::string blender(const std::string& script);
  // The frame rendered: the last of the sequence.
  std::filesystem::path vdbFrame() const;
  // Samples per pixel of Cycles and of sixway's traced light: SIXWAY_CYCLES_SPP, else 256 (the suite's).
  static std::string samples();
  // Written to the test artifacts as cycles_<name>.json and printed.
  static void report(const std::string& name, const nlohmann::json& report);

  TempDir dir_;
};

}  // namespace sixway::test
