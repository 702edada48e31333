#include "app/render_command.h"

#include <sixway/device.h>
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/device_limits.h"
#include "app/frame_writer.h"
#include "app/options.h"
#include "app/process_memory.h"
#include "app/scene_errors.h"
#include "app/shipped_weights.h"
#include "app/staged_directory.h"
#include "app/stop_on_signal.h"
#include "app/timings_log.h"
#include "io/error.h"
#include "io/report.h"
#include "metrics/image_metrics.h"
#include "modes/mode_renderer.h"
#include "modes/scene_source.h"
#include "runtime/internal.h"
#include "runtime/scene_volumes.h"
#include "scene/scene.h"

namespace sixway::app {
namespace {

namespace fs = std::filesystem;

struct RenderOptions {
  CommonOptions common;
  fs::path scene, out, weights;
  int frames = 0;
  std::optional<std::string> mode;
  bool force = false, exr = false, video = false, fp16 = false, noShadows = false;
  int fps = 30;
  std::optional<int> warmup;           // default: the scene's render.warmup_frames
  std::optional<std::string> toneMap;  // default: the scene's render.tone_map
  std::optional<float> exposureStops;  // default: the scene's render.exposure
  uint32_t samples = 64;
  int orders = 64;
  reference::MultipleScattering multiple;
};

// The frames of one mode, all from the runtime's one real-time frame: neural through the public
// SmokeRenderer (the product's path, as an engine runs it); the evaluation's modes through
// modes::ModeRenderer on the same simulation. A VDB scene has no simulation for the public API to run: every
// mode, neural included, goes through ModeRenderer on the played-back volumes.
class FrameSource {
 public:
  FrameSource(sixway::Device& device, sixway::SmokeSimulation* simulation, render::VolumeSequence* playback,
              const scene::Scene& scene, const fs::path& scenePath, const modes::ModeOptions& options)
      : simulation_(simulation), playback_(playback), scene_(scene) {
    const std::string settings = "render.lightmap_size, render.width or render.height";
    if (options.mode == modes::RenderMode::Neural && simulation) {
      sixway::RendererOptions rendererOptions;
      rendererOptions.weights = options.weights;
      rendererOptions.fp16 = options.fp16;
      rendererOptions.shadows = options.shadows;
      renderer_ = withinDeviceLimits(scenePath.string(), settings, [&] {
        return std::make_unique<sixway::SmokeRenderer>(device, *simulation, rendererOptions);
      });
    } else {
      modeRenderer_ = withinDeviceLimits(scenePath.string(), settings, [&] {
        return std::make_unique<modes::ModeRenderer>(runtime::Access::context(device),
                                                     runtime::Access::pipelineCache(device), scene, options);
      });
    }
  }

  // Frame `index`: its image, GPU stage times and notes (the simulation has been advanced to it).
  modes::RenderedFrame render(int index) {
    if (modeRenderer_)
      return modeRenderer_->render(
          index, runtime::SimulatedVolumes::frameSeconds(scene_, index),
          playback_ ? playback_->volume(index) : runtime::Access::volumes(*simulation_).currentVolume());
    renderer_->render();
    modes::RenderedFrame frame;
    frame.image = io::Image(int(renderer_->width()), int(renderer_->height()), {"R", "G", "B", "A"});
    frame.image.pixels = renderer_->image();
    for (const sixway::StageTime& t : renderer_->stageTimes())
      frame.stages.push_back({t.name, t.milliseconds});
    frame.notes = renderer_->notes();
    return frame;
  }

 private:
  sixway::SmokeSimulation* simulation_;
  render::VolumeSequence* playback_;
  const scene::Scene& scene_;
  std::unique_ptr<sixway::SmokeRenderer> renderer_;
  std::unique_ptr<modes::ModeRenderer> modeRenderer_;
};

void run(const RenderOptions& o) {
  const StopOnSignal stopOnSignal;
  scene::Scene scene = scene::loadScene(o.scene);
  if (o.warmup) scene.render.warmupFrames = *o.warmup;
  if (o.toneMap) scene.render.toneMap = *o.toneMap == "aces" ? scene::ToneMap::Aces : scene::ToneMap::Clamp;
  if (o.exposureStops) scene.render.exposureStops = *o.exposureStops;
  // Warm-up frames run the scene's clock (simulation, camera and light paths) without writing; frame_0000 is
  // the scene's frame `warmup`.
  const int warmup = scene.render.warmupFrames;
  modes::ModeOptions options;
  options.weights = resolveWeights(o.weights);
  // Without --mode: the network when the shipped weights exist, else the reference lightmaps (said on the
  // terminal). Weights named with --weights always mean the network, so a missing file is an error, not a
  // silent change of mode.
  const bool network = !o.weights.empty() || fs::exists(options.weights);
  options.mode = o.mode ? modes::parseRenderMode(*o.mode)
                        : (network ? modes::RenderMode::Neural : modes::RenderMode::Reference);
  // Not an error: scripts loop over the modes with one set of options.
  if (!o.weights.empty() && options.mode != modes::RenderMode::Neural)
    std::fprintf(stderr, "sixway: note: --weights %s is not used: --mode %s uses no network\n",
                 o.weights.c_str(), modes::renderModeName(options.mode));
  options.fp16 = o.fp16;
  options.shadows = !o.noShadows;
  options.pathTraceSamples = o.samples;
  options.pathTraceOrders = o.orders;
  options.multipleScattering = o.multiple;
  // A directory or special file under a name the render replaces stops it here, before any work.
  StagedDirectory::requireWritable(o.out, o.force, FrameWriter::isRenderOutput);

  sixway::Device device(o.common.deviceOptions());
  std::optional<sixway::SmokeSimulation> simulation;
  std::unique_ptr<render::VolumeSequence> playback;
  if (scene.vdb) {
    playback = withinDeviceLimits(o.scene.string(), "vdb.voxels", [&] {
      return modes::openSceneVolumes(runtime::Access::context(device), runtime::Access::pipelineCache(device),
                                     scene, warmup + o.frames, o.scene.string());
    });
  } else {
    withinDeviceLimits(o.scene.string(), gridSetting(scene.grid), [&] {
      simulation.emplace(device, o.scene);
      return true;
    });
  }
  FrameSource source(device, simulation ? &*simulation : nullptr, playback.get(), scene, o.scene, options);
  // The output directory appears only once everything it needs has been checked.
  FrameWriterOptions writerOptions;
  writerOptions.exr = o.exr;
  writerOptions.video = o.video;
  writerOptions.fps = o.fps;
  writerOptions.display = {scene.render.toneMap, scene.render.exposureStops};
  writerOptions.frames = o.frames;
  writerOptions.force = o.force;
  FrameWriter writer(o.out, writerOptions);
  std::printf("sixway render: %s, %d frames, mode %s, %dx%d (lightmaps %d²), on %s\n", scene.name.c_str(),
              o.frames, modes::renderModeName(options.mode), scene.render.width, scene.render.height,
              scene.render.lightmapSize, device.name().c_str());
  std::fflush(stdout);
  TimingsLog timings(o.frames);
  // Per frame: the fraction of pixels the smoke covers (alpha ≥ 0.1); none in the modes without alpha
  // (guide).
  std::vector<double> coverage;
  coverage.reserve(size_t(o.frames));
  // Per frame: pixels no renderer should make (metrics::imageFaults), in the modes with alpha.
  nlohmann::json faults = nlohmann::json::array();
  uint64_t faultTotal = 0;
  namingScene(o.scene, [&] {
    if (simulation)
      for (int w = 0; w < warmup; ++w) {
        throwIfStopped();
        simulation->advance();
        std::printf("  warm-up %d/%d\n", w + 1, warmup);
        std::fflush(stdout);
      }
    const auto started = std::chrono::steady_clock::now();
    for (int i = 0; i < o.frames; ++i) {
      throwIfStopped();
      if (simulation) simulation->advance();
      const modes::RenderedFrame frame = source.render(warmup + i);
      writer.write(i, frame.image);
      if (frame.image.channelCount() == 4) {
        coverage.push_back(metrics::alphaCoverage(frame.image));
        const metrics::ImageFaults f = metrics::imageFaults(frame.image);
        faults.push_back({{"not_finite", f.notFinite},
                          {"negative", f.negative},
                          {"dark_dots", f.darkDots},
                          {"first_pixels", f.first}});
        faultTotal += f.total();
        if (f.total() > 0)
          std::fprintf(stderr, "sixway: frame %d has %s\n", i, metrics::describeFaults(f).c_str());
      }
      for (const std::string& note : frame.notes) std::fprintf(stderr, "sixway: note: %s\n", note.c_str());

      std::vector<gpu::StageTime> stages;
      if (simulation)
        for (const sixway::StageTime& t : simulation->stageTimes())
          stages.push_back({t.name, t.milliseconds});
      stages.insert(stages.end(), frame.stages.begin(), frame.stages.end());
      // Memory in use, for long-run checks: flat from the first frames on, or something leaks.
      const sixway::Device::MemoryUse memory = device.memoryUse();
      const double total = timings.add(i, runtime::SimulatedVolumes::frameSeconds(scene, warmup + i), stages,
                                       {memory.allocations, memory.bytes}, residentSetBytes());
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      std::printf("  frame %d/%d: %.1f ms GPU, %.1f s elapsed, ETA %.0f s\n", i + 1, o.frames, total, elapsed,
                  elapsed / (i + 1) * (o.frames - i - 1));
      std::fflush(stdout);
    }
  });
  const std::vector<std::string> extras = writer.finish();

  nlohmann::json report = {{"scene", fs::absolute(o.scene).string()},
                           {"mode", modes::renderModeName(options.mode)},
                           {"device", device.name()},
                           {"size", {scene.render.width, scene.render.height}},
                           {"lightmap_size", scene.render.lightmapSize},
                           {"warmup_frames", warmup},
                           {"median_stage_ms", timings.medianStageMs()},
                           {"frames", timings.frames()}};
  // The last 16 frames' least coverage: a run that ends on a developed plume fills the picture there.
  const auto lastFrames = coverage.end() - std::min<ptrdiff_t>(16, ptrdiff_t(coverage.size()));
  const double leastCoverage = coverage.empty() ? 0.0 : *std::min_element(lastFrames, coverage.end());
  if (!coverage.empty()) {
    report["coverage"] = {
        {"alpha_threshold", 0.1}, {"per_frame", coverage}, {"least_of_last_16", leastCoverage}};
    report["pixel_faults"] = {{"total", faultTotal}, {"per_frame", faults}};
  }
  if (options.mode == modes::RenderMode::Neural) report["weights"] = fs::absolute(options.weights).string();
  if (playback) report["source"] = modes::describeSource(*playback);
  io::writeReport(writer.stagedPath("timings.json"), report);
  writer.commit();
  std::printf("sixway render: wrote %d frames, timings.json", o.frames);
  for (const std::string& f : extras) std::printf(", %s", f.c_str());
  std::printf(" to %s\n", o.out.string().c_str());
  if (!coverage.empty())
    std::printf("sixway render: the smoke covers %.1f%% of the picture at least, over the last %td frames\n",
                100.0 * leastCoverage, coverage.end() - lastFrames);
  requireNoValidationMessages(device);
}

}  // namespace

void addRenderCommand(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* render =
      app.add_subcommand("render", "Headless frame capture of a scene's simulation or VDB playback");
  o->common.addTo(*render);
  render->add_option("--scene", o->scene, "Scene JSON")->required()->check(filePath());
  render->add_option("--frames", o->frames, "Frames rendered")->required()->check(CLI::Range(1, 100000));
  render->add_option("--out", o->out, "Output directory")->required()->check(directoryPath());
  render->add_flag("--force", o->force, "Write into an existing output directory");
  render->add_option(
      "--mode", o->mode,
      "neural | reference | reference-ms | traditional | traditional-ms | guide | guide-lit | pathtrace "
      "(default: neural when the weights exist, else reference)");
  render->add_option("--weights", o->weights, kWeightsHelp)->check(filePath());
  render->add_flag("--fp16", o->fp16, "Neural: fp16 feature maps");
  render->add_flag("--no-shadows", o->noShadows, "No obstacle shadows on the smoke");
  render->add_option("--spp", o->samples, "Pathtrace: samples per pixel (default 64)")
      ->check(CLI::Range(1, 1 << 20));
  render
      ->add_option("--orders", o->orders, "Pathtrace: scattering orders (default 64; 1 = single scattering)")
      ->check(CLI::Range(1, 100000));
  render
      ->add_option("--ms-spp", o->multiple.samples,
                   "reference-ms/traditional-ms: samples per traced pixel of the orders >= 2 (default 64)")
      ->check(CLI::Range(1, 1 << 20));
  render
      ->add_option("--ms-downsample", o->multiple.downsample,
                   "reference-ms/traditional-ms: orders >= 2 traced at 1/N of the lightmap size (default 1)")
      ->check(CLI::IsMember({1, 2, 4, 8}));
  render->add_flag("--exr", o->exr, "Also write each frame as a linear EXR");
  render->add_flag("--video", o->video, "Also write video.mp4 (needs ffmpeg)");
  render->add_option("--fps", o->fps, "Video frame rate (default 30)")->check(CLI::Range(1, 240));
  render
      ->add_option(
          "--warmup", o->warmup,
          "Frames simulated before the first one written (default: the scene's render.warmup_frames)")
      ->check(CLI::Range(0, 100000));
  render
      ->add_option("--tone-map", o->toneMap,
                   "PNG/video display transform: clamp | aces (default: the scene's render.tone_map)")
      ->check(CLI::IsMember({"clamp", "aces"}));
  render
      ->add_option("--exposure", o->exposureStops,
                   "PNG/video exposure in stops, before the tone map (default: the scene's render.exposure)")
      ->check(CLI::Range(-20.0, 20.0));
  render->callback([o] { run(*o); });
}

}  // namespace sixway::app
