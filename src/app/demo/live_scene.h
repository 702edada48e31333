#pragma once
// The demo's scene, as an engine holds it through the public API (include/sixway/): a SmokeSimulation
// running frame by frame (pause, step, reset, inlet strength, obstacles dragged by the user) and a
// SmokeRenderer for neural mode; the evaluation's other modes (reference, traditional, guide, ...) through
// modes::ModeRenderer on the same simulation. Renderers are built on first use, one per mode and shadow
// setting, and all see the simulation's obstacle motions. A scene that plays OpenVDB files back has no
// simulation for the public API to run: its frames loop, and every mode (neural too) is a ModeRenderer.
#include <sixway/device.h>
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>

#include <filesystem>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "gpu/sequence.h"
#include "modes/mode_renderer.h"
#include "render/volume_sequence.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Context;
class Image;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::app::demo {

inline constexpr uint32_t kMaxDemoLights = 4;  // lights with a shadow-atlas tile each

// The lights of the scene's first frame, held still (the user moves them now), at most kMaxDemoLights.
std::vector<scene::Light> startingLights(const scene::Scene& scene);

struct LiveSceneOptions {
  std::filesystem::path weights;  // the network file for neural mode
  bool fp16 = false;
};

// A rendered view's images on the GPU (VK_IMAGE_LAYOUT_GENERAL, sampled) and its GPU stage times.
struct LiveFrame {
  const gpu::Image* color = nullptr;  // RGBA16F linear, premultiplied
  const gpu::Image* guide = nullptr;  // guide light, alpha, shell depth
  const gpu::Image* lightmapA = nullptr;
  const gpu::Image* lightmapB = nullptr;
  std::vector<gpu::StageTime> stages;
};

class LiveScene {
 public:
  // Loads the scene (io::InputError naming it) on the demo's window device.
  LiveScene(gpu::Context& context, gpu::PipelineCache& cache, const std::filesystem::path& scene,
            const LiveSceneOptions& options);

  const scene::Scene& scene() const;
  // Simulates the next frame. Throws sim::WatchdogError when the flow diverges.
  void advance();
  // The simulation from its start, obstacles back on the scene's motions.
  void reset();
  int frame() const { return simulation_ ? simulation_->framesSimulated() - 1 : playedFrame_; }
  double seconds() const;

  size_t obstacleCount() const { return simulation_ ? simulation_->obstacleCount() : 0; }
  glm::vec3 obstaclePosition(size_t obstacle) const { return simulation_->obstaclePosition(obstacle); }
  // Drags the obstacle toward `target` (SmokeSimulation::steerObstacle); the renderers follow.
  void steerObstacle(size_t obstacle, glm::vec3 target);
  void setInletStrength(float strength);  // clamped to [0, maxInletStrength()]
  float inletStrength() const { return simulation_ ? simulation_->inletStrength() : 0.0f; }
  float maxInletStrength() const { return simulation_ ? simulation_->maxInletStrength() : 0.0f; }
  // GPU time of the last advance()'s simulation steps.
  std::vector<gpu::StageTime> simulationTimes() const;

  // Renders the current frame in `mode` from `camera` under `lights`, with or without obstacle shadows.
  // Throws io::InputError when neural mode has no weights file.
  LiveFrame render(modes::RenderMode mode, const Camera& camera, const std::vector<scene::Light>& lights,
                   bool shadows);

 private:
  LiveFrame renderNeural(const Camera& camera, const std::vector<scene::Light>& lights, bool shadows);
  modes::ModeRenderer& modeRendererFor(modes::RenderMode mode, bool shadows);
  void followObstacles();

  Device device_;  // around the demo's context
  LiveSceneOptions options_;
  std::unique_ptr<SmokeSimulation> simulation_;       // a simulated scene
  scene::Scene playedScene_;                          // a played-back scene, its grid the playback lattice
  std::unique_ptr<render::VolumeSequence> playback_;  // its files
  int playedFrame_ = 0;
  std::map<bool, std::unique_ptr<SmokeRenderer>> renderers_;  // neural, by shadows
  std::map<std::pair<modes::RenderMode, bool>, std::unique_ptr<modes::ModeRenderer>> modeRenderers_;
};

}  // namespace sixway::app::demo
