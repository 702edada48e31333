// Timings of the reference renderers for docs/benchmarks.md ("Reference rendering"): the full
// eight-channel bake of a 256² lightmap from a 128³ volume, and the path tracer's samples per second.
// GPU timestamps of the gpu::Sequence stages, median of 5 runs after a warm-up run.
// The volume: tests/data/vdb/densityAndHeat.vdb resampled onto a 128³ cube of cubic cells around it.
// Usage: reference_bench
#include <algorithm>
#include <cstdio>
#include <glm/geometric.hpp>
#include <map>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "reference/lightmap_baker.h"
#include "reference/path_tracer.h"
#include "render/billboard.h"
#include "vdb_cube.h"

namespace {

using namespace sixway;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

void benchBake(reference::LightmapBaker& baker, const render::Volume& volume, const scene::Smoke& smoke,
               const render::Camera& camera, const char* view) {
  reference::BakeSettings settings;
  settings.width = settings.height = 256;
  const render::ImagePlane billboard = render::billboardBounds(camera, volume.grid.bounds(), 1.0f);
  std::map<std::string, std::vector<double>> stages;
  std::vector<double> totals;
  for (int run = 0; run < 6; ++run) {
    baker.bake(volume, smoke, camera, billboard, settings);
    if (run == 0) continue;  // warm-up
    double total = 0;
    for (const gpu::StageTime& t : baker.stageTimes()) {
      total += t.milliseconds;
      stages[t.name].push_back(t.milliseconds);
    }
    totals.push_back(total);
  }
  uint64_t nodes = 0;
  for (const render::LightGrid& g : baker.lightGrids()) nodes = std::max(nodes, g.nodeCount());
  std::printf("bake 256x256, 8 channels, %s view: %.1f ms (light grids up to %.1f M nodes)\n", view,
              median(totals), nodes / 1e6);
  for (const auto& [name, times] : stages) std::printf("  %-24s %.1f ms\n", name.c_str(), median(times));
}

void benchTrace(reference::PathTracer& tracer, const render::Volume& volume, const scene::Smoke& smoke,
                const render::Camera& camera, int orders) {
  reference::TraceSettings settings;
  settings.width = settings.height = 256;
  settings.maxOrders = orders;
  settings.samplesPerPass = 4;
  const render::ImagePlane billboard = render::billboardBounds(camera, volume.grid.bounds(), 1.0f);
  std::vector<double> rates;
  for (int run = 0; run < 6; ++run) {
    tracer.beginSixWay(volume, smoke, camera, billboard, settings);
    tracer.accumulate(8);
    if (run > 0) rates.push_back(256.0 * 256.0 * tracer.samples() / (tracer.traceMilliseconds() * 1e-3));
  }
  std::printf("path tracer, six-way lightmaps 256x256, %d scattering order%s: %.3g samples/s\n", orders,
              orders == 1 ? "" : "s", median(rates));
}

}  // namespace

int main() {
  gpu::Context context;
  gpu::PipelineCache cache(context);
  std::printf("device: %s (%s)\n", context.properties().deviceName, context.driver().driverInfo);

  const render::DeviceVolume volume = render::uploadVolume(context, test::densityAndHeatCube(128));

  scene::Smoke smoke;  // about 0.3 optical depth per cell at the densest cells, as in the simulated scenes
  smoke.extinction = 0.3f / volume.grid().cellSize;
  const render::Box box = volume.grid().bounds();
  const render::Camera front = render::framingCamera(box);
  const render::Camera oblique = render::Camera::lookAt(
      box.centre() + glm::length(box.size()) * glm::vec3(0.9f, 0.6f, 1.2f), box.centre(), {0, 1, 0}, 40.0f);

  reference::LightmapBaker baker(context, cache);
  benchBake(baker, volume.view(), smoke, front, "front (axis-aligned)");
  benchBake(baker, volume.view(), smoke, oblique, "oblique");
  reference::PathTracer tracer(context, cache);
  benchTrace(tracer, volume.view(), smoke, front, 1);
  benchTrace(tracer, volume.view(), smoke, front, 64);
  return 0;
}
