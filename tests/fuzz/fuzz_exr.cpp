// OpenEXR files through io::readExr (every channel, then the flipbook's R, G, B, A by name). OpenEXR's own
// exceptions must come out as io::InputError.
#include <cstddef>
#include <cstdint>

#include "fuzz_input_file.h"
#include "io/error.h"
#include "io/exr.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const auto path = sixway::fuzz::writeInput("fuzz.exr", data, size);
  try {
    sixway::io::readExr(path);
  } catch (const sixway::io::InputError&) {
  }
  try {
    sixway::io::readExr(path, {"R", "G", "B", "A"});
  } catch (const sixway::io::InputError&) {
  }
  return 0;
}
