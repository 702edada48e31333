#pragma once
// What a sixway::SmokeRenderer holds: the real-time frame with the network as its lightmap source, and this
// frame's camera and lights. sixway's own tools reach the frame's images through runtime::Access (the demo
// displays them).
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>

#include <optional>
#include <vector>

#include "render/engine_view.h"
#include "runtime/frame_renderer.h"
#include "scene/scene.h"

namespace sixway {

struct SmokeRenderer::Impl {
  // `engineFormat`: the colour format of the engine's targets; none: sixway's own image.
  Impl(const gpu::Context& context, const gpu::PipelineCache& cache, const SmokeSimulation& simulation,
       const RendererOptions& options, std::optional<VkFormat> engineFormat);

  // This frame of the simulation's volume: the sequence to submit or record (with an engine target, all but
  // the composite).
  gpu::Sequence& prepare();
  // Records the frame into the engine's `targets` with the layout changes they ask for.
  void record(VkCommandBuffer commands, uint64_t frame, const FrameTargets& targets);

  const gpu::Context& context;
  const SmokeSimulation& simulation;
  const scene::Scene& scene;  // the simulation's
  bool engineTarget;
  runtime::FrameRenderer renderer;
  std::optional<FrameTargets> fixedTargets;  // the RenderTarget constructor's
  std::optional<render::EngineView> view;    // setCamera's or setViewProjection's
  bool planeFromTarget = false;              // setCamera's: the view's plane is the target's full frame
  std::optional<std::vector<scene::Light>> lights;
  gpu::Sequence* last = nullptr;
  gpu::Sequence* lastComposite = nullptr;
};

}  // namespace sixway
