#pragma once
// What a sixway::SmokeRenderer holds: the real-time frame with the network as its lightmap stage, recorded
// once per simulation volume and replayed, and this frame's camera and lights. sixway's own tools reach the
// frame's images through runtime::Access (the demo displays them).
#include <sixway/smoke_renderer.h>

#include <memory>
#include <optional>

#include "nn/network.h"
#include "render/recorded_sequence.h"
#include "runtime/realtime_frame.h"

namespace sixway {

struct SmokeRenderer::Impl {
  Impl(const gpu::Context& context, const gpu::PipelineCache& cache, const SmokeSimulation& simulation,
       const RendererOptions& options, const RenderTarget* target);

  // Records the passes for the simulation's volume (once) and writes this frame's values.
  gpu::Sequence& prepare();

  const SmokeSimulation& simulation;
  const io::Scene& scene;  // the simulation's
  bool engineTarget;
  std::unique_ptr<nn::Network> network;  // before the frame, whose guide it sets
  runtime::RealtimeFrame frame;
  render::RecordedSequence sequence;
  std::optional<Camera> camera;
  std::optional<std::vector<io::Light>> lights;
  std::vector<std::string> notes;  // of the last frame
  gpu::Sequence* last = nullptr;
};

}  // namespace sixway
