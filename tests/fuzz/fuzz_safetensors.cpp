// Weights files: io::readSafetensors, then the network graph in their metadata with its tensor checks
// (nn::parseGraph), as `sixway render --weights` reads them before any device work.
#include <cstddef>
#include <cstdint>

#include "fuzz_input_file.h"
#include "io/error.h"
#include "io/safetensors.h"
#include "nn/graph.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  try {
    const sixway::io::SafetensorsFile file =
        sixway::io::readSafetensors(sixway::fuzz::writeInput("fuzz.safetensors", data, size));
    sixway::nn::parseGraph(file);
  } catch (const sixway::io::InputError&) {
  }
  return 0;
}
