// OpenVDB files through our wrapper (io::readVdbInfo, io::readVdbGrids onto a small automatic lattice), as
// `sixway bake --vdb` and `sixway info` read them. OpenVDB's own exceptions must come out as io::InputError.
#include <cstddef>
#include <cstdint>

#include "fuzz_input_file.h"
#include "io/error.h"
#include "io/vdb.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  try {
    const auto path = sixway::fuzz::writeInput("fuzz.vdb", data, size);
    sixway::io::readVdbInfo(path);
    sixway::io::readVdbGrids(path, {}, sixway::io::AutoBounds{16});
  } catch (const sixway::io::InputError&) {
  }
  return 0;
}
