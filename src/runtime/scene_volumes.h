#pragma once
// The volumes of a scene's simulation, frame after frame, for `sixway bake --scene` and `sixway render`. This
// is the one place where the renderers meet the simulation: the smoke goes from the simulation's
// grid to the renderers' volume buffers on the GPU.
#include <memory>
#include <optional>

#include "gpu/sequence.h"
#include "render/volume.h"
#include "render/volume_sequence.h"
#include "scene/scene.h"
#include "sim/simulation.h"

namespace sixway::gpu {
class Context;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::runtime {

// Frame i is the smoke after i + 1 frames of simulation (t = (i + 1) · time.frame_dt); `frames` frames.
class SimulatedVolumes : public render::VolumeSequence {
 public:
  SimulatedVolumes(const gpu::Context& context, const gpu::PipelineCache& cache, const scene::Scene& scene,
                   int frames);

  int frameCount() const override { return frames_; }
  // Nothing for a frame without smoke.
  std::optional<render::Volume> frame(int index) override;
  render::Box bounds() const override { return volume_.grid().bounds(); }
  std::string frameName(int index) const override;
  float cellSize() const override { return volume_.grid().cellSize; }
  // The inlets' largest density: the smoke's transport makes no new maxima (docs/simulation.md, "Smoke").
  float densityBound(int, int) override { return densityBound_; }

  // The volume of frame `index` even when it is empty; indices in increasing order.
  render::Volume volume(int index) override;
  // Records the next frame's simulation (`steps` lattice steps, unset: the scene's per frame) and the smoke's
  // export into the volume into `commands`, a caller's command buffer, as frame `frame`; nothing waits
  // (sim::Simulation::record).
  void recordFrame(VkCommandBuffer commands, uint64_t frame, std::optional<uint32_t> steps = std::nullopt);
  // The volume the frames are exported into (its buffers stay the same).
  render::Volume currentVolume() const { return volume_.view(); }
  // The simulation itself (e.g. its velocity, lbm().macro(), for `sixway dataset`'s motion field).
  const sim::Simulation& simulation() const { return simulation_; }
  sim::Simulation& simulation() { return simulation_; }
  // GPU time of the simulation steps of the last frame asked for (ms).
  const sim::StepTimes& frameTimes() const { return frameTimes_; }
  static double frameSeconds(const scene::Scene& scene, int index) {
    return double(index + 1) * scene.time.frameDt;
  }

 private:
  sim::Simulation simulation_;
  int frames_;
  int simulated_ = 0;  // frames simulated so far
  float densityBound_ = 0;
  render::DeviceVolume volume_;
  gpu::Sequence exportSmoke_;  // the simulation's smoke into volume_, on the GPU
  sim::StepTimes frameTimes_;
};

}  // namespace sixway::runtime
