#pragma once
// What a sixway::SmokeRenderer holds: the real-time frame with the network as its lightmap source, and this
// frame's camera and lights. sixway's own tools reach the frame's images through runtime::Access (the demo
// displays them).
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>

#include <optional>
#include <variant>
#include <vector>

#include "gpu/frame_timestamps.h"
#include "render/engine_view.h"
#include "runtime/frame_renderer.h"
#include "runtime/network_lightmaps.h"
#include "scene/scene.h"

namespace sixway {

struct SmokeRenderer::Impl {
  // `engine`: the engine's targets' colour format or rendering's formats; none: sixway's own image.
  Impl(const gpu::Context& context, const gpu::PipelineCache& cache, const SmokeSimulation& simulation,
       const RendererOptions& options, std::optional<runtime::FrameTarget> engine);

  // This frame of the simulation's volume: the sequence to submit or record (with an engine target, all but
  // the composite); `frame`: the engine's frame number (none on sixway's own device).
  gpu::Sequence& prepare(std::optional<uint64_t> frame);
  // Records the frame into the engine's `targets` with the layout changes they ask for.
  void record(VkCommandBuffer commands, uint64_t frame, const FrameTargets& targets);

  // The network's lightmaps: its own network, or RendererOptions::shareNetwork's.
  static std::unique_ptr<runtime::NetworkLightmaps> networkSource(const gpu::Context& context,
                                                                  const gpu::PipelineCache& cache,
                                                                  const scene::Scene& scene,
                                                                  const RendererOptions& options);

  // The renderer's lightmap source: always the network's.
  runtime::NetworkLightmaps& network() { return static_cast<runtime::NetworkLightmaps&>(renderer.source()); }
  const runtime::NetworkLightmaps& network() const {
    return static_cast<const runtime::NetworkLightmaps&>(renderer.source());
  }

  const gpu::Context& context;
  const SmokeSimulation& simulation;
  const scene::Scene& scene;  // the simulation's
  bool engineTarget;          // the engine's images or rendering
  bool insideRendering;       // the engine's rendering (recordLightmaps, recordComposite)
  runtime::FrameRenderer renderer;
  // The simulation's obstacles the meshes were made for: its start and obstacle set (sim::Simulation::
  // obstacleSetsMade).
  std::pair<uint64_t, uint64_t> obstaclesOf;
  // The camera and lights in the scene this frame (the engine's, through the simulation's placement).
  std::optional<render::EngineView> sceneView() const;
  std::optional<std::vector<scene::Light>> sceneLights() const;

  std::optional<FrameTargets> fixedTargets;  // the RenderTarget constructor's
  struct Matrices {
    glm::mat4 view, projection;
  };
  std::variant<std::monostate, Camera, Matrices> camera;  // setCamera's or setViewProjection's, in the world
  std::optional<std::vector<Light>> lights;               // setLights', in the world
  gpu::Sequence* last = nullptr;
  std::optional<gpu::FrameTimestamps> compositeTimes;  // inside the engine's rendering: "shade"
  gpu::Sequence* lastComposite = nullptr;
};

}  // namespace sixway
