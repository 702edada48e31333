#pragma once
// One frame of a scene in one of the modes of `sixway render`: the runtime's real-time frame
// (runtime/frame_renderer.h) with the mode's lightmap source, or the path tracer's image over that frame's
// rasterized background:
//   neural       guiding map → network → six-way shading (runtime::NetworkLightmaps)
//   reference    the reference baker's lightmaps (exact single scattering) → the same shading
//   reference-ms multiply-scattered lightmaps (ScatteredLightmaps) → the same shading: the best any six-way
//                method can do with the axis-lit maps under full transport
//   reference-fit the six maps fitted to the smoke lit from many directions (FittedLightmaps) → the same
//                shading: the ceiling of six-way lighting
//   traditional  a flipbook baked from the first frame's view, on a camera-facing billboard (today's games)
//   traditional-ms  the same flipbook baked with multiple scattering (what DCC tools bake)
//   guide        the guiding map itself (guide, alpha, shell depth)
//   guide-lit    the guiding map's mean light as all six lightmaps → the same shading (no network: the
//                evaluation's "guide only" baseline)
//   pathtrace    the volumetric path tracer (ground truth), over the rasterized background
// This layer links the reference renderers (src/reference/); the runtime below it does not.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gpu/sequence.h"
#include "io/image.h"
#include "modes/path_traced_smoke.h"
#include "modes/render_mode.h"
#include "render/volume.h"
#include "runtime/frame_renderer.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Context;
class Image;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::modes {

struct RenderedFrame {
  io::Image image;  // R, G, B, A (linear; the guide's channels in guide mode); empty without download
  std::vector<gpu::StageTime> stages;  // GPU time per stage of this frame
  std::vector<std::string> notes;      // for the user, e.g. a light without a shadow map
};

class ModeRenderer {
 public:
  // Builds every pass the mode needs for the scene. Throws io::InputError for missing or malformed weights.
  ModeRenderer(const gpu::Context& context, const gpu::PipelineCache& cache, const scene::Scene& scene,
               const ModeOptions& options);
  ModeRenderer(const ModeRenderer&) = delete;
  ModeRenderer& operator=(const ModeRenderer&) = delete;

  // Frame `index` (camera and lights on their paths, obstacles at `seconds`) of `volume`.
  RenderedFrame render(int index, double seconds, const render::Volume& volume);
  // The same from `view`; `index` still seeds the per-frame jitter and noise.
  RenderedFrame render(const runtime::FrameView& view, int index, double seconds,
                       const render::Volume& volume);
  // Moves obstacle `obstacle` along `motion` from now on (the simulation's, when a user drags it).
  void setObstacleMotion(size_t obstacle, std::optional<scene::Motion> motion);

  // Of the last frame, for tests and evaluation: the guiding map (guide, alpha, shell depth), its opacity
  // depths (render::GuidingMap::opacityDepths: four channels, encoded) and the lightmaps
  // (sixWayChannelNames() order).
  io::Image guide() const;
  io::Image opacityDepths() const;
  io::Image lightmaps() const;
  // The images on the GPU (VK_IMAGE_LAYOUT_GENERAL, sampled), valid while the renderer lives: the frame
  // (RGBA16F linear, premultiplied, the scene's render size; the path tracer's smoke is composited on the
  // host only), the guiding map and the two lightmaps in Unity's packing (lightmap size).
  const gpu::Image& colorImage() const;
  const gpu::Image& guideImage() const;
  const gpu::Image& lightmapImageA() const;
  const gpu::Image& lightmapImageB() const;

 private:
  scene::Scene scene_;
  scene::Scene raster_;  // what the real-time passes draw: pathtrace draws the obstacles itself
  ModeOptions options_;
  runtime::FrameRenderer frame_;
  std::unique_ptr<PathTracedSmoke> pathTraced_;  // pathtrace
};

}  // namespace sixway::modes
