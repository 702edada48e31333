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
  Impl(const gpu::Context& context, const gpu::PipelineCache& cache, const SmokeSimulation& simulation,
       const RendererOptions& options, const RenderTarget* target);

  // This frame of the simulation's volume: the sequence to submit or record.
  gpu::Sequence& prepare();

  const SmokeSimulation& simulation;
  const scene::Scene& scene;  // the simulation's
  bool engineTarget;
  runtime::FrameRenderer renderer;
  std::optional<render::EngineView> view;  // setCamera's or setViewProjection's
  std::optional<std::vector<scene::Light>> lights;
  gpu::Sequence* last = nullptr;
};

}  // namespace sixway
