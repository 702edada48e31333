#pragma once
// `sixway eval --scene`: a scene's sequence (its own camera and light paths; the simulation live) rendered
// frame by frame by every method and measured (docs/results.md):
//   - the network's lightmaps against the reference baker's, same view (lightmap PSNR,
//     docs/conventions.md, "Metrics");
//   - the final images of neural, reference-lightmap (single and multiple scattering), traditional-flipbook
//     (single and multiple scattering) and guide-lit rendering against the path tracer (ground truth);
//   - GPU time per stage of every method and of the simulation;
//   - the path tracer at the neural frame's time (equal_time.h), and a side-by-side strip of one frame;
//   - each method's frame-to-frame change against the truth's (temporal_change.h).
// Obstacles are drawn by every method and path-traced in the truth (opaque surfaces that hide, shadow and are
// shadowed by the smoke); --no-obstacles leaves them out of every image (they still shape the flow), for
// studying the lightmaps alone.
#include <sixway/device.h>

#include <filesystem>
#include <optional>

#include "reference/scattered_lightmaps.h"

namespace sixway::eval {

struct SceneEvalSettings {
  std::filesystem::path scene, weights, report, out;  // out: strip.png (none when empty)
  int frames = 0;
  uint32_t samples = 64;                             // path-tracer ground truth, per pixel
  int orders = 64;                                   // its scattering orders
  reference::MultipleScattering multipleScattering;  // of reference-ms, reference-fit and traditional-ms
  // > 0: also the reference-fit method, its six maps fitted to the smoke lit from this many directions
  // (reference/fitted_lightmaps.h; about directions / 6 times reference-ms's cost)
  int fitDirections = 0;
  float densityScale = 1.0f;
  bool shadows = true, obstacles = true;  // obstacles: drawn, and in the truth
  std::optional<float> cameraOrbitDeg;    // replaces the scene's camera path by an orbit (degrees per frame)
  std::optional<int> stripFrame;          // default: the last frame
  uint32_t equalTimeReferenceSamples = 256;
  bool equalTime = true;  // false: no equal-time study (the report's equal_time is null)
  // Path-trace every frame a second time with another seed, so that the truth's frame-to-frame change can be
  // told from its noise (temporal_change.h); doubles the truth's cost.
  bool truthNoise = false;
  bool force = false;
};

// On sixway's own device of `device`.
void evaluateScene(const DeviceOptions& device, const SceneEvalSettings& settings);

}  // namespace sixway::eval
