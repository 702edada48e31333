#pragma once
// One rendered frame of a scene, stage by stage (DESIGN.md §1), in one of the modes of `sixway render`:
//   neural       guiding map → network → six-way shading
//   reference    the reference baker's lightmaps (exact single scattering) → the same shading
//   traditional  a flipbook baked from the first frame's view, on a camera-facing billboard (today's games)
//   guide        the guiding map itself (guide, alpha, shell depth)
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
#include "render/volume.h"

namespace sixway::gpu {
class Context;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::app {

enum class RenderMode { Neural, Reference, Traditional, Guide, PathTrace };

// "neural", "reference", ...; throws io::InputError (source "--mode") for another name.
RenderMode parseRenderMode(const std::string& name);
const char* renderModeName(RenderMode mode);

struct FramePipelineOptions {
  RenderMode mode = RenderMode::Neural;
  std::filesystem::path weights;   // neural: the network file
  bool fp16 = false;               // neural: fp16 feature maps where the device has 16-bit storage
  bool shadows = true;             // obstacle shadows on the smoke
  uint32_t pathTraceSamples = 64;  // pathtrace: samples per pixel
  int pathTraceOrders = 64;        // pathtrace: scattering orders (1: single scattering, like the baker)
};

struct RenderedFrame {
  io::Image image;                     // R, G, B, A (linear; the guide's channels in guide mode)
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
  // Of the last frame: the guiding map (guide, alpha, shell depth) and the lightmaps (sixWayChannelNames()
  // order; the network's, the baker's or the flipbook's), for tests and evaluation.
  io::Image guide() const;
  io::Image lightmaps() const;

 private:
  struct Passes;
  std::unique_ptr<Passes> passes_;
};

}  // namespace sixway::app
