#include "app/scene_volumes.h"

#include <algorithm>
#include <cstdio>

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
                true) {}

  int frameCount() const override { return frames_; }

  std::optional<render::Volume> frame(int index) override {
    const uint32_t steps = uint32_t(io::lbmStepsPerFrame(simulation_.scene()));
    for (; simulated_ <= index; ++simulated_) simulation_.advance(steps);
    // The simulation keeps density and temperature interleaved on the GPU; they travel through the host into
    // the two buffers the renderers read.
    const auto [density, temperature] = simulation_.smokeGrids();
    if (std::none_of(density.values.begin(), density.values.end(), [](float v) { return v > 0.0f; }))
      return std::nullopt;
    volume_.upload(density.values, temperature.values);
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
};

}  // namespace

std::unique_ptr<render::VolumeSequence> simulatedVolumes(const gpu::Context& context,
                                                         const gpu::PipelineCache& cache,
                                                         const io::Scene& scene, int frames) {
  return std::make_unique<SimulatedVolumes>(context, cache, scene, frames);
}

}  // namespace sixway::app
