#pragma once
// The side-by-side strip of one evaluated frame (`sixway eval --scene --out DIR`): the ground truth, then
// each method, then each method's error |method − truth| (mean over R, G, B, × gain) in false colour, for
// people.
#include <filesystem>
#include <string>
#include <vector>

#include "io/image.h"

namespace sixway::eval {

struct StripPanel {
  std::string name;  // for the report; the strip itself carries no text
  const io::Image* image;
};

// Writes `path` (8-bit PNG): `truth`, the `methods`, then the methods' error maps, each panel scaled up by a
// whole factor to at least `minHeight` pixels. Returns the panel names left to right.
std::vector<std::string> writeEvalStrip(const std::filesystem::path& path, const io::Image& truth,
                                        const std::vector<StripPanel>& methods, float errorGain = 4.0f,
                                        int minHeight = 128);

}  // namespace sixway::eval
