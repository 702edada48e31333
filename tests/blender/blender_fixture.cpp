#include "blender/blender_fixture.h"

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>

namespace sixway::test {

namespace fs = std::filesystem;

void BlenderFixture::SetUp() {
  run(blender("mantaflow_smoke.py") + " '" +
          (fs::path(SIXWAY_BLENDER_TEST_DIR) / "mantaflow_fire.json").string() + "' '" +
          (dir_ / "vdb").string() + "'",
      dir_ / "mantaflow.log");
}

void BlenderFixture::run(const std::string& command, const fs::path& log) {
  const int status = std::system((command + " > '" + log.string() + "' 2>&1").c_str());
  if (status == 0) return;
  std::ifstream in(log);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  FAIL() << "failed (" << status << "): " << command << "\n"
         << text.substr(text.size() > 3000 ? text.size() - 3000 : 0);
}

std::string BlenderFixture::blender(const std::string& script) {
  return "blender -b --factory-startup --python-exit-code 1 --python '" +
         (fs::path(SIXWAY_BLENDER_SCRIPTS) / script).string() + "' --";
}

fs::path BlenderFixture::vdbFrame() const {
  return dir_ / "vdb" / "smoke_0015.vdb";
}

std::string BlenderFixture::samples() {
  const char* given = std::getenv("SIXWAY_CYCLES_SPP");
  return given ? given : "256";
}

void BlenderFixture::report(const std::string& name, const nlohmann::json& report) {
  fs::create_directories(SIXWAY_TEST_ARTIFACT_DIR);
  std::ofstream(fs::path(SIXWAY_TEST_ARTIFACT_DIR) / ("cycles_" + name + ".json")) << report.dump(1);
  std::cout << report.dump(1) << "\n";
}

}  // namespace sixway::test
