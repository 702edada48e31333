#include "runtime/scene_volumes.h"

#include <cstdio>

#include "scene/fluid_physics.h"

namespace sixway::runtime {

SimulatedVolumes::SimulatedVolumes(const gpu::Context& context, const gpu::PipelineCache& cache,
                                   const scene::Scene& scene, int frames)
    : simulation_(context, cache, scene),
      frames_(frames),
      volume_(
          context,
          {simulation_.smoke().size(), scene.grid.origin, scene.grid.cellSize / float(scene.grid.smokeUpres)},
          true),
      exportSmoke_(context) {
  simulation_.smoke().recordExport(exportSmoke_, volume_.density(), volume_.temperature());
  exportSmoke_.finish();
  for (const scene::Inlet& inlet : scene.inlets) densityBound_ = std::max(densityBound_, inlet.density);
}

render::Volume SimulatedVolumes::volume(int index) {
  const uint32_t steps = uint32_t(scene::lbmStepsPerFrame(simulation_.scene()));
  if (simulated_ <= index) frameTimes_ = {};
  for (; simulated_ <= index; ++simulated_) {
    simulation_.advance(steps);
    const sim::StepTimes& t = simulation_.report().times;
    frameTimes_.obstacles += t.obstacles;
    frameTimes_.forces += t.forces;
    frameTimes_.lbm += t.lbm;
    frameTimes_.smoke += t.smoke;
    frameTimes_.watchdog += t.watchdog;
  }
  exportSmoke_.submit();
  return volume_.view();
}

void SimulatedVolumes::recordFrame(VkCommandBuffer commands, uint64_t frame, std::optional<uint32_t> steps) {
  if (steps)
    simulation_.record(commands, frame, *steps);
  else
    simulation_.record(commands, frame);
  exportSmoke_.record(commands, frame);
  ++simulated_;
}

std::optional<render::Volume> SimulatedVolumes::frame(int index) {
  const render::Volume v = volume(index);
  if (simulation_.report().maxDensity <= 0.0f) return std::nullopt;
  return v;
}

std::string SimulatedVolumes::frameName(int index) const {
  char name[64];
  std::snprintf(name, sizeof(name), "t = %.3f s", frameSeconds(simulation_.scene(), index));
  return name;
}

}  // namespace sixway::runtime
