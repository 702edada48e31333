// TGA textures (flipbooks from other tools) through io::readTga (stb_image).
#include <cstddef>
#include <cstdint>

#include "fuzz_input_file.h"
#include "io/error.h"
#include "io/tga.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  try {
    sixway::io::readTga(sixway::fuzz::writeInput("fuzz.tga", data, size));
  } catch (const sixway::io::InputError&) {
  }
  return 0;
}
