#pragma once
// The modes of `sixway render` (mode_renderer.h), by their command-line names, and their options.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "reference/scattered_lightmaps.h"

namespace sixway::modes {

enum class RenderMode {
  Neural,
  Reference,
  ReferenceMs,
  ReferenceFit,
  Traditional,
  TraditionalMs,
  Guide,
  GuideLit,
  PathTrace
};

// "neural", "reference", ...; throws io::InputError (source "--mode") for another name.
RenderMode parseRenderMode(const std::string& name);
const char* renderModeName(RenderMode mode);

struct ModeOptions {
  RenderMode mode = RenderMode::Neural;
  std::filesystem::path weights;  // neural: the network file
  bool fp16 = false;              // neural: fp16 feature maps where the device has 16-bit storage
  bool shadows = true;  // obstacle shadows on the smoke (pathtrace: on the smoke and on the obstacles)
  uint32_t pathTraceSamples = 64;    // pathtrace: samples per pixel
  int pathTraceOrders = 64;          // pathtrace: scattering orders (1: single scattering, like the baker)
  uint32_t pathTraceSeedOffset = 0;  // pathtrace: added to its seed (render.seed + frame): other noise
  // reference-ms, traditional-ms: the higher orders' tracing (its seed is the scene's render.seed + frame)
  reference::MultipleScattering multipleScattering;
  int fitDirections =
      36;  // reference-fit: light directions the six maps are fitted to (reference/fitted_lightmaps.h)
  // Shadow atlas tiles; unset: one per shadow-casting light of the scene (the demo reserves room for the
  // lights a user may add).
  std::optional<uint32_t> shadowTiles;
  bool download = true;  // read the frame back into RenderedFrame::image (the demo displays it on the GPU)
};

}  // namespace sixway::modes
