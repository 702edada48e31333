// `sixway bench` sections "lightmaps" and "frame": the real-time stages of the neural render mode
// (runtime/frame_renderer.h: shadow maps, obstacles, guiding map, network, six-way shading) at fixed lightmap
// sizes, beside the exact single-scattering baker they replace (the same volume, camera and size, in the same
// run), and the whole frame of the paper's setting: one frame of simulation plus those stages.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include "app/bench_options.h"
#include "app/bench_scene.h"
#include "app/bench_stats.h"
#include "gpu/check.h"
#include "gpu/context.h"
#include "io/error.h"
#include "modes/mode_renderer.h"
#include "render/volume.h"
#include "scene/fluid_physics.h"
#include "sim/simulation.h"

namespace sixway::app {
namespace {

modes::ModeOptions neuralMode(const BenchOptions& o, bool fp16) {
  modes::ModeOptions options;
  options.mode = modes::RenderMode::Neural;
  options.weights = o.weights;
  options.fp16 = fp16;
  return options;
}

// The network's stage named by the precision of its feature maps, so that both can sit in one table.
void addFrameStages(StageTimes& times, const std::vector<gpu::StageTime>& stages, bool fp16 = false) {
  for (const gpu::StageTime& t : stages)
    times.add(t.name == "network" ? (fp16 ? "network fp16" : "network fp32") : t.name, t.milliseconds);
}

// The GPU time of a stage, or of the stages whose names start with `prefix` + "/".
double stageMs(const std::vector<gpu::StageTime>& stages, const std::string& name) {
  double ms = 0.0;
  for (const gpu::StageTime& t : stages)
    if (t.name == name || t.name.starts_with(name + "/")) ms += t.milliseconds;
  return ms;
}

constexpr const char* kNeuralRow = "neural lightmaps: guide + network fp32";
constexpr const char* kBakerRow = "exact baker (single scattering)";

nlohmann::json sceneSettings(const scene::Scene& scene) {
  return {{"lattice", {scene.grid.size.x, scene.grid.size.y, scene.grid.size.z}},
          {"frame", {scene.render.width, scene.render.height}},
          {"lights", scene.lights.size()},
          {"obstacles", scene.obstacles.size()}};
}

}  // namespace

nlohmann::json benchLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache,
                              const BenchOptions& o, const BenchInputs& inputs) {
  scene::Scene scene = benchScene(o.scene, inputs.lattices.front());
  const std::vector<glm::vec2> smoke = benchSmoke(scene);
  std::vector<float> density(smoke.size()), temperature(smoke.size());
  for (size_t i = 0; i < smoke.size(); ++i) density[i] = smoke[i].x, temperature[i] = smoke[i].y;
  const render::VolumeGrid grid{scene.grid.size * scene.grid.smokeUpres, scene.grid.origin,
                                scene.grid.cellSize / float(scene.grid.smokeUpres)};
  render::DeviceVolume volume(context, grid, true);
  volume.upload(density, temperature);
  const bool fp16 = context.capabilities().storage16Bit;
  std::printf(
      "\nlightmaps: %dx%d frame, the bench plume on a %dx%dx%d grid, network %s%s\n", scene.render.width,
      scene.render.height, grid.size.x, grid.size.y, grid.size.z, o.weights.filename().string().c_str(),
      fp16 ? " (fp32 and fp16 feature maps)" : " (fp32 feature maps; no 16-bit storage on this device)");

  nlohmann::json sizes = nlohmann::json::array();
  for (uint32_t size : o.sizes) {
    scene.render.lightmapSize = int(size);
    modes::ModeRenderer neural(context, cache, scene, neuralMode(o, false));
    std::unique_ptr<modes::ModeRenderer> half;
    if (fp16) half = std::make_unique<modes::ModeRenderer>(context, cache, scene, neuralMode(o, true));
    modes::ModeOptions exact;
    exact.mode = modes::RenderMode::Reference;
    modes::ModeRenderer baker(context, cache, scene, exact);
    const auto render = [&](StageTimes* times) {
      const modes::RenderedFrame frame = neural.render(0, 0.0, volume.view());
      const std::vector<gpu::StageTime> halfStages =
          half ? half->render(0, 0.0, volume.view()).stages : std::vector<gpu::StageTime>{};
      const modes::RenderedFrame baked = baker.render(0, 0.0, volume.view());
      if (!times) return;
      times->beginRun();
      addFrameStages(*times, frame.stages);
      for (const gpu::StageTime& t : halfStages)
        if (t.name == "network") times->add("network fp16", t.milliseconds, false);
      times->add(kNeuralRow, stageMs(frame.stages, "guide") + stageMs(frame.stages, "network"), false);
      times->add(kBakerRow, stageMs(baked.stages, "bake"), false);
    };
    for (int i = 0; i < o.warmup; ++i) render(nullptr);
    StageTimes times;
    for (int r = 0; r < o.repeats; ++r) render(&times);
    times.print("  " + std::to_string(size) + "x" + std::to_string(size) + " lightmaps");
    const double neuralMs = summarize(times.samples(kNeuralRow)).median,
                 bakerMs = summarize(times.samples(kBakerRow)).median;
    std::printf("  neural lightmaps / exact baker: %.3f / %.3f ms = %.2fx (medians)\n", neuralMs, bakerMs,
                neuralMs / bakerMs);
    nlohmann::json entry = times.json();
    entry["size"] = size;
    entry["neural_over_baker"] = neuralMs / bakerMs;
    sizes.push_back(entry);
  }
  nlohmann::json report = sceneSettings(scene);
  report.update({{"scene", o.scene.string()},
                 {"weights", o.weights.string()},
                 {"fp16", fp16},
                 {"warmup", o.warmup},
                 {"repeats", o.repeats},
                 {"sizes", sizes}});
  return report;
}

nlohmann::json benchFrame(const gpu::Context& context, const gpu::PipelineCache& cache, const BenchOptions& o,
                          const BenchInputs& inputs) {
  scene::Scene scene = benchScene(o.scene, inputs.lattices.front());
  scene.render.lightmapSize = int(o.frameLightmapSize);
  const uint32_t steps = uint32_t(scene::lbmStepsPerFrame(scene));
  const bool fp16 = o.fp16 && context.capabilities().storage16Bit;
  std::printf("\nframe: %d lattice steps of %dx%dx%d + %ux%u lightmaps (%s maps) + a %dx%d frame\n", steps,
              scene.grid.size.x, scene.grid.size.y, scene.grid.size.z, o.frameLightmapSize,
              o.frameLightmapSize, fp16 ? "fp16" : "fp32", scene.render.width, scene.render.height);
  std::fflush(stdout);
  std::unique_ptr<sim::Simulation> simulation;
  try {
    simulation = std::make_unique<sim::Simulation>(context, cache, scene);
  } catch (const gpu::GpuError& e) {
    throw io::InputError("--grid " + std::to_string(scene.grid.size.x) + "x" +
                             std::to_string(scene.grid.size.y) + "x" + std::to_string(scene.grid.size.z),
                         e.what());
  }
  simulation->smoke().upload(benchSmoke(scene));
  // The smoke into the renderers' volume buffers, as app/scene_volumes.cpp hands it over every frame.
  render::DeviceVolume volume(
      context,
      {simulation->smoke().size(), scene.grid.origin, scene.grid.cellSize / float(scene.grid.smokeUpres)},
      true);
  gpu::Sequence exportSmoke(context);
  exportSmoke.beginStage("smoke export");
  simulation->smoke().recordExport(exportSmoke, volume.density(), volume.temperature());
  exportSmoke.endStage();
  exportSmoke.finish();
  modes::ModeRenderer neural(context, cache, scene, neuralMode(o, fp16));

  int index = 0;
  const auto frame = [&](StageTimes* times) {
    simulation->advance(steps);
    exportSmoke.submit();
    const modes::RenderedFrame rendered = neural.render(index, simulation->seconds(), volume.view());
    ++index;
    if (!times) return;
    const sim::StepTimes& t = simulation->report().times;
    times->beginRun();
    times->add("simulation: obstacles", t.obstacles);
    if (simulation->obstacles().obstacleCount() > 0) times->add("simulation: forces", t.forces);
    times->add("simulation: lbm", t.lbm);
    times->add("simulation: smoke", t.smoke);
    times->add("simulation: watchdog", t.watchdog);
    times->add(exportSmoke.stageTimes());
    addFrameStages(*times, rendered.stages, fp16);
  };
  for (int i = 0; i < o.warmup; ++i) frame(nullptr);
  StageTimes times;
  std::vector<double> simulationMs, renderingMs, wallMs;
  for (int r = 0; r < o.repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    frame(&times);
    wallMs.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    const sim::StepTimes& t = simulation->report().times;
    simulationMs.push_back(t.total() + exportSmoke.stageTimes().front().milliseconds);
    renderingMs.push_back(times.totals().back() - simulationMs.back());
  }
  times.print("  end-to-end frame");
  const Timing wall = summarize(wallMs);
  std::printf("  simulation %.3f ms + real-time rendering %.3f ms (medians); wall clock %.3f ms per frame\n",
              summarize(simulationMs).median, summarize(renderingMs).median, wall.median);
  std::fflush(stdout);

  nlohmann::json report = times.json();
  report.update(sceneSettings(scene));
  report.update({{"scene", o.scene.string()},
                 {"weights", o.weights.string()},
                 {"lightmap_size", o.frameLightmapSize},
                 {"steps_per_frame", steps},
                 {"precision", fp16 ? "fp16" : "fp32"},
                 {"warmup", o.warmup},
                 {"simulation", timingJson(simulationMs)},
                 {"rendering", timingJson(renderingMs)},
                 {"wall", timingJson(wallMs)}});
  return report;
}

}  // namespace sixway::app
