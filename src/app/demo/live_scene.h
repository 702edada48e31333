#pragma once
// The demo's scene: the simulation running frame by frame (pause, step, reset, inlet strength, obstacles
// dragged by the user) and the frame pipelines that render it, one per mode the user has looked at, built on
// first use. Every pipeline and the simulation see the same obstacle motions.
#include <filesystem>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "eval/frame_pipeline.h"
#include "io/scene.h"
#include "runtime/scene_volumes.h"

namespace sixway::gpu {
class Context;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::app::demo {

inline constexpr uint32_t kMaxDemoLights = 4;  // lights with a shadow-atlas tile each

// The lights of the scene's first frame, held still (the user moves them now), at most kMaxDemoLights.
std::vector<io::Light> startingLights(const io::Scene& scene);

struct LiveSceneOptions {
  std::filesystem::path weights;  // the network file for neural mode
  bool fp16 = false;
};

class LiveScene {
 public:
  LiveScene(const gpu::Context& context, const gpu::PipelineCache& cache, const io::Scene& scene,
            const LiveSceneOptions& options);

  const io::Scene& scene() const { return scene_; }
  // Simulates the next frame. Throws sim::WatchdogError when the flow diverges.
  void advance();
  // The simulation from its start, obstacles back on the scene's motions.
  void reset();
  int frame() const { return frame_; }
  double seconds() const { return runtime::SimulatedVolumes::frameSeconds(scene_, frame_); }

  size_t obstacleCount() const { return scene_.obstacles.size(); }
  glm::vec3 obstaclePosition(size_t obstacle) const;  // world, now
  // Drags the obstacle toward `target` (sim::Simulation::steerObstacle); the renderers follow.
  void steerObstacle(size_t obstacle, glm::vec3 target);
  void setInletStrength(float strength);  // clamped to [0, maxInletStrength()]
  float inletStrength() const { return volumes_->simulation().inletStrength(); }
  float maxInletStrength() const { return volumes_->simulation().maxInletStrength(); }
  const sim::StepTimes& simulationTimes() const { return volumes_->frameTimes(); }

  // Renders the current frame in `mode` from `view`, with or without obstacle shadows (one pipeline each).
  // Throws io::InputError when neural mode has no weights file.
  eval::RenderedFrame render(eval::RenderMode mode, const eval::FrameView& view, bool shadows);
  // The pipeline of the last render() in that mode (its images stay on the GPU).
  const eval::FramePipeline& pipeline(eval::RenderMode mode, bool shadows);

 private:
  eval::FramePipeline& pipelineFor(eval::RenderMode mode, bool shadows);

  const gpu::Context& context_;
  const gpu::PipelineCache& cache_;
  io::Scene scene_;
  LiveSceneOptions options_;
  std::unique_ptr<runtime::SimulatedVolumes> volumes_;
  std::map<std::pair<eval::RenderMode, bool>, std::unique_ptr<eval::FramePipeline>> pipelines_;
  int frame_ = 0;
};

}  // namespace sixway::app::demo
