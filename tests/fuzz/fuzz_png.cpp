// PNG textures (flipbooks from other tools) through io::readPng (stb_image).
#include <cstddef>
#include <cstdint>

#include "fuzz_input_file.h"
#include "io/error.h"
#include "io/png.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  try {
    sixway::io::readPng(sixway::fuzz::writeInput("fuzz.png", data, size));
  } catch (const sixway::io::InputError&) {
  }
  return 0;
}
