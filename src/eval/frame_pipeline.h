#pragma once
// One rendered frame of a scene, stage by stage (docs/conventions.md, "The frame"), in one of the modes of
// `sixway render`:
//   neural       guiding map → network → six-way shading
//   reference    the reference baker's lightmaps (exact single scattering) → the same shading
//   reference-ms multiply-scattered lightmaps (ScatteredLightmaps) → the same shading: the best any six-way
//                method can do under full transport
//   traditional  a flipbook baked from the first frame's view, on a camera-facing billboard (today's games)
//   traditional-ms  the same flipbook baked with multiple scattering (what DCC tools bake)
//   guide        the guiding map itself (guide, alpha, shell depth)
//   guide-lit    the guiding map's mean light as all six lightmaps → the same shading (no network: the
//                evaluation's "guide only" baseline)
//   pathtrace    the volumetric path tracer (ground truth), over the rasterized obstacles
// The real-time stages (shadow maps, obstacles, guiding map, network, shading) are recorded once into one
// sequence and replayed every frame; only per-frame values travel from the host. docs/real-time-rendering.md.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gpu/sequence.h"
#include "io/image.h"
#include "io/scene.h"
#include "reference/scattered_lightmaps.h"
#include "render/camera.h"
#include "render/volume.h"

namespace sixway::gpu {
class Context;
class Image;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::eval {

enum class RenderMode {
  Neural,
  Reference,
  ReferenceMs,
  Traditional,
  TraditionalMs,
  Guide,
  GuideLit,
  PathTrace
};

// "neural", "reference", ...; throws io::InputError (source "--mode") for another name.
RenderMode parseRenderMode(const std::string& name);
const char* renderModeName(RenderMode mode);

struct FramePipelineOptions {
  RenderMode mode = RenderMode::Neural;
  std::filesystem::path weights;  // neural: the network file
  bool fp16 = false;              // neural: fp16 feature maps where the device has 16-bit storage
  bool shadows = true;  // obstacle shadows on the smoke (pathtrace: on the smoke and on the obstacles)
  uint32_t pathTraceSamples = 64;    // pathtrace: samples per pixel
  int pathTraceOrders = 64;          // pathtrace: scattering orders (1: single scattering, like the baker)
  uint32_t pathTraceSeedOffset = 0;  // pathtrace: added to its seed (render.seed + frame): other noise
  // reference-ms, traditional-ms: the higher orders' tracing (its seed is the scene's render.seed + frame)
  render::MultipleScattering multipleScattering;
  // Shadow atlas tiles; unset: one per shadow-casting light of the scene (the demo reserves room for the
  // lights a user may add).
  std::optional<uint32_t> shadowTiles;
  bool download = true;  // read the frame back into RenderedFrame::image (the demo displays it on the GPU)
};

// Where a frame is seen from and what lights it: the scene's camera and lights on their paths, or a user's.
struct FrameView {
  render::Camera camera;
  std::vector<io::Light> lights;
};
FrameView sceneView(const io::Scene& scene, int index);

struct RenderedFrame {
  io::Image image;  // R, G, B, A (linear; the guide's channels in guide mode); empty without download
  std::vector<gpu::StageTime> stages;  // GPU time per stage of this frame
  std::vector<std::string> notes;      // for the user, e.g. a light without a shadow map
};

class FramePipeline {
 public:
  // Builds every pass the mode needs for the scene. Throws io::InputError for missing or malformed weights.
  FramePipeline(const gpu::Context& context, const gpu::PipelineCache& cache, const io::Scene& scene,
                const FramePipelineOptions& options);
  ~FramePipeline();

  // Frame `index` (camera and lights on their paths, obstacles at `seconds`) of `volume`.
  RenderedFrame render(int index, double seconds, const render::Volume& volume);
  // The same from `view`; `index` still seeds the per-frame jitter and the path tracer.
  RenderedFrame render(const FrameView& view, int index, double seconds, const render::Volume& volume);
  // Of the last frame: the guiding map (guide, alpha, shell depth) and the lightmaps (sixWayChannelNames()
  // order; the network's, the baker's or the flipbook's), for tests and evaluation.
  io::Image guide() const;
  // The guide's opacity depths of the last frame (render::GuidingMap::opacityDepths): four channels, encoded.
  io::Image opacityDepths() const;
  // Moves obstacle `obstacle` along `motion` from now on (the simulation's, when a user drags it).
  void setObstacleMotion(size_t obstacle, std::optional<io::Motion> motion);
  io::Image lightmaps() const;
  // The images on the GPU (VK_IMAGE_LAYOUT_GENERAL, sampled), valid until the pipeline is destroyed: the
  // frame (RGBA16F linear, premultiplied, the scene's render size; the path tracer's smoke is composited on
  // the host only), the guiding map and the two lightmaps in Unity's packing (lightmap size).
  const gpu::Image& colorImage() const;
  const gpu::Image& guideImage() const;
  const gpu::Image& lightmapImageA() const;
  const gpu::Image& lightmapImageB() const;

 private:
  struct Passes;
  std::unique_ptr<Passes> passes_;
};

}  // namespace sixway::eval
