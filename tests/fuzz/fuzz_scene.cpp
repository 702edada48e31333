// Scene files (docs/scene-format.md): JSON text → scene::parseScene. Bad input must end in io::InputError;
// any other exception, crash or sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_input_file.h"
#include "io/error.h"
#include "io/json_reader.h"
#include "scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    // Mesh paths are only resolved against the folder here, not opened.
    sixway::scene::parseScene(sixway::io::parseJsonText(text, "fuzz.json"), "fuzz.json",
                              sixway::fuzz::scratchDirectory());
  } catch (const sixway::io::InputError&) {
  }
  return 0;
}
