// The network graph's JSON (`sixway.graph`, docs/network-format.md) alone: mutating it inside a weights
// file's header rarely keeps the header valid, so the schema checks of nn::parseGraphJson get their own
// target.
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/error.h"
#include "nn/graph.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  try {
    sixway::nn::parseGraphJson(std::string(reinterpret_cast<const char*>(data), size), "fuzz.safetensors");
  } catch (const sixway::io::InputError&) {
  }
  return 0;
}
