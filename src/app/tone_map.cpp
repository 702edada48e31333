#include "app/tone_map.h"

#include <algorithm>
#include <cmath>

namespace sixway::app {

float acesFitted(float x) {
  x = std::max(x, 0.0f);
  return std::clamp(x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}

io::Image toDisplay(const io::Image& linear, const DisplayTransform& transform) {
  const float scale = std::exp2(transform.exposureStops);
  io::Image rgb(linear.width, linear.height, {"R", "G", "B"});
  for (int y = 0; y < linear.height; ++y)
    for (int x = 0; x < linear.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const float v = linear.at(x, y, c) * scale;
        rgb.at(x, y, c) =
            transform.toneMap == scene::ToneMap::Aces ? acesFitted(v) : std::clamp(v, 0.0f, 1.0f);
      }
  return rgb;
}

}  // namespace sixway::app
