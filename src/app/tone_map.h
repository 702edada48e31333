#pragma once
// The display transform of `sixway render`'s PNG frames, contact sheet and video: exposure, then a tone map,
// then (in io::writePng) the sRGB encoding. The frame itself, its EXR and the lightmaps stay linear HDR, as
// an engine embedding the renderer would want them for its own tone mapping.
#include "io/image.h"
#include "scene/scene.h"

namespace sixway::app {

struct DisplayTransform {
  scene::ToneMap toneMap = scene::ToneMap::Clamp;
  float exposureStops = 0;  // multiplies the linear values by 2^exposureStops
};

// Narkowicz's fit of the ACES RRT+ODT (sRGB, 2016): x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14), clamped to
// [0, 1]; pre-exposed so that 1 maps to about 0.8 (fit error ≤ 0.014 per its author). Per channel.
float acesFitted(float x);

// The RGB of `linear` (RGB or RGBA; alpha dropped) in display-linear [0, 1], ready for sRGB encoding.
io::Image toDisplay(const io::Image& linear, const DisplayTransform& transform);

}  // namespace sixway::app
