// Prints the agreement of lightmaps with a reference (masked PSNR, docs/conventions.md, "Metrics"), for the
// bake-against-Cycles race of tools/blender/flipbook_race.sh. Built with the tests, not a test.
//   compare_lightmaps TESTED REFERENCE
// TESTED, REFERENCE: a `sixway bake` frame (frames/frame_NNNN.exr) or a folder that
// tools/blender/cycles_lightmaps.py wrote. Prints "light_db emissive_db alpha_db".
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "blender/cycles_agreement.h"

namespace fs = std::filesystem;
using namespace sixway::test;

namespace {

Render read(const fs::path& path) {
  return fs::is_directory(path) ? readCyclesLightmaps(path) : readBakedFrame(path);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: compare_lightmaps TESTED REFERENCE\n";
    return 1;
  }
  try {
    const std::vector<Render> tested = {read(argv[1])}, reference = {read(argv[2])};
    std::printf("%.2f %.2f %.2f\n", compareRenders(tested, reference, {0, 1, 2, 3, 4, 5}).psnrDb(),
                compareRenders(tested, reference, {6}).psnrDb(), compareAlpha(tested, reference).psnrDb());
  } catch (const std::exception& e) {
    std::cerr << "compare_lightmaps: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
