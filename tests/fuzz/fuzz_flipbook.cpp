// Flipbook sidecars (reference::readFlipbook): the fuzzed description is read next to real textures, a 2×2
// flipbook of 4×3 tiles in Unity's packing written once by reference::writeFlipbook (book_A.exr/.png/.tga,
// book_B.*), so descriptions that survive the JSON checks go on to read, check and unpack them.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_input_file.h"
#include "io/error.h"
#include "reference/flipbook.h"

namespace {

void writeTextures() {
  const sixway::reference::FlipbookLayout layout = sixway::reference::flipbookLayout(3, 4, 3, 2);
  std::vector<sixway::io::Image> frames;
  for (int f = 0; f < layout.frames; ++f) {
    const auto& names = sixway::render::sixWayChannelNames();
    sixway::io::Image frame(layout.tileWidth, layout.tileHeight, {names.begin(), names.end()});
    for (std::size_t i = 0; i < frame.pixels.size(); ++i) frame.pixels[i] = float((i * 7 + f) % 11) / 10.0f;
    frames.push_back(frame);
  }
  sixway::reference::writeFlipbook(sixway::fuzz::scratchDirectory(), "book", frames, layout,
                                   sixway::reference::unityPacking(), {});
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  writeTextures();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  try {
    sixway::reference::readFlipbook(sixway::fuzz::writeInput("fuzz.json", data, size));
  } catch (const sixway::io::InputError&) {
  }
  return 0;
}
