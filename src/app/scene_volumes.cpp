#include "app/scene_volumes.h"

#include <cstdio>

#include "gpu/sequence.h"
#include "render/volume.h"
#include "sim/simulation.h"

namespace sixway::app {
namespace {

class SimulatedVolumes : public render::VolumeSequence {
 public:
  SimulatedVolumes(const gpu::Context& context, const gpu::PipelineCache& cache, const io::Scene& scene,
                   int frames)
      : simulation_(context, cache, scene),
        frames_(frames),
        volume_(context,
                {simulation_.smoke().size(), scene.grid.origin,
                 scene.grid.cellSize / float(scene.grid.smokeUpres)},
                true),
        exportSmoke_(context) {
    simulation_.smoke().recordExport(exportSmoke_, volume_.density(), volume_.temperature());
    exportSmoke_.finish();
  }

  int frameCount() const override { return frames_; }

  std::optional<render::Volume> frame(int index) override {
    const uint32_t steps = uint32_t(io::lbmStepsPerFrame(simulation_.scene()));
    for (; simulated_ <= index; ++simulated_) simulation_.advance(steps);
    if (simulation_.report().maxDensity <= 0.0f) return std::nullopt;
    exportSmoke_.submit();
    return volume_.view();
  }

  render::Box bounds() const override { return volume_.grid().bounds(); }

  std::string frameName(int index) const override {
    char name[64];
    std::snprintf(name, sizeof(name), "t = %.3f s", double(index + 1) * simulation_.scene().time.frameDt);
    return name;
  }

 private:
  sim::Simulation simulation_;
  int frames_;
  int simulated_ = 0;  // frames simulated so far
  render::DeviceVolume volume_;
  gpu::Sequence exportSmoke_;  // the simulation's smoke into volume_, on the GPU
};

}  // namespace

std::unique_ptr<render::VolumeSequence> simulatedVolumes(const gpu::Context& context,
                                                         const gpu::PipelineCache& cache,
                                                         const io::Scene& scene, int frames) {
  return std::make_unique<SimulatedVolumes>(context, cache, scene, frames);
}

}  // namespace sixway::app
