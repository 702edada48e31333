// Wavefront OBJ meshes (obstacles) through io::readObj: our vertex-line checks, then tinyobjloader and our
// checks of its indices.
#include <cstddef>
#include <cstdint>

#include "fuzz_input_file.h"
#include "io/error.h"
#include "io/obj.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  try {
    sixway::io::readObj(sixway::fuzz::writeInput("fuzz.obj", data, size));
  } catch (const sixway::io::InputError&) {
  }
  return 0;
}
