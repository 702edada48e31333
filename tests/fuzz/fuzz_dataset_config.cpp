// Dataset configs (dataset::loadDatasetConfig), which also read the base scene they name: the fuzzed config lies
// next to base.json (a copy of assets/scenes/plume.json) and the bunny mesh, which the seeds name.
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "dataset/dataset_config.h"
#include "fuzz_input_file.h"
#include "io/error.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const std::filesystem::path& scratch = sixway::fuzz::scratchDirectory();
  std::filesystem::copy_file(SIXWAY_ASSETS_DIR "/scenes/plume.json", scratch / "base.json");
  std::filesystem::copy_file(SIXWAY_ASSETS_DIR "/meshes/stanford-bunny.obj", scratch / "bunny.obj");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  try {
    sixway::dataset::loadDatasetConfig(sixway::fuzz::writeInput("config.json", data, size));
  } catch (const sixway::io::InputError&) {
  }
  return 0;
}
