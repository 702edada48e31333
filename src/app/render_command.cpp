#include "app/render_command.h"

#include <sixway/device.h>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/frame_writer.h"
#include "app/options.h"
#include "app/render_frame_loop.h"
#include "app/render_frame_source.h"
#include "app/scene_errors.h"
#include "app/shipped_weights.h"
#include "app/staged_directory.h"
#include "app/stop_on_signal.h"
#include "io/report.h"
#include "modes/mode_renderer.h"
#include "modes/scene_source.h"
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
  int fitDirections = 36;
};

// The scene with the command line's display settings.
scene::Scene renderedScene(const RenderOptions& o) {
  scene::Scene scene = scene::loadScene(o.scene);
  if (o.warmup) scene.render.warmupFrames = *o.warmup;
  if (o.toneMap) scene.render.toneMap = *o.toneMap == "aces" ? scene::ToneMap::Aces : scene::ToneMap::Clamp;
  if (o.exposureStops) scene.render.exposureStops = *o.exposureStops;
  return scene;
}

modes::ModeOptions modeOptions(const RenderOptions& o) {
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
  options.fitDirections = o.fitDirections;
  return options;
}

FrameWriterOptions writerOptions(const RenderOptions& o, const scene::Scene& scene) {
  FrameWriterOptions options;
  options.exr = o.exr;
  options.video = o.video;
  options.fps = o.fps;
  options.display = {scene.render.toneMap, scene.render.exposureStops};
  options.frames = o.frames;
  options.force = o.force;
  return options;
}

nlohmann::json report(const RenderOptions& o, const scene::Scene& scene, const modes::ModeOptions& options,
                      const sixway::Device& device, const RenderFrameSource& source,
                      const RenderFrameLoop& frames) {
  nlohmann::json report = {{"scene", fs::absolute(o.scene).string()},
                           {"mode", modes::renderModeName(options.mode)},
                           {"device", device.name()},
                           {"size", {scene.render.width, scene.render.height}},
                           {"lightmap_size", scene.render.lightmapSize},
                           {"warmup_frames", scene.render.warmupFrames},
                           {"median_stage_ms", frames.timings().medianStageMs()},
                           {"frames", frames.timings().frames()}};
  frames.addChecks(report);
  if (options.mode == modes::RenderMode::Neural) report["weights"] = fs::absolute(options.weights).string();
  if (source.playback()) report["source"] = modes::describeSource(*source.playback());
  return report;
}

void run(const RenderOptions& o) {
  const StopOnSignal stopOnSignal;
  scene::Scene scene = renderedScene(o);
  // Warm-up frames run the scene's clock (simulation, camera and light paths) without writing; frame_0000 is
  // the scene's frame `warmup`.
  const int warmup = scene.render.warmupFrames;
  const modes::ModeOptions options = modeOptions(o);
  // A directory or special file under a name the render replaces stops it here, before any work.
  StagedDirectory::requireWritable(o.out, o.force, FrameWriter::isRenderOutput);

  sixway::Device device(o.common.deviceOptions());
  RenderFrameSource source(device, scene, o.scene, warmup + o.frames, options);
  // The output directory appears only once everything it needs has been checked.
  FrameWriter writer(o.out, writerOptions(o, scene));
  std::printf("sixway render: %s, %d frames, mode %s, %dx%d (lightmaps %d²), on %s\n", scene.name.c_str(),
              o.frames, modes::renderModeName(options.mode), scene.render.width, scene.render.height,
              scene.render.lightmapSize, device.name().c_str());
  std::fflush(stdout);
  RenderFrameLoop frames(device, scene, source, writer, o.frames);
  namingScene(o.scene, [&] {
    source.warmUp(warmup);
    frames.run(warmup);
  });
  const std::vector<std::string> extras = writer.finish();
  io::writeReport(writer.stagedPath("timings.json"), report(o, scene, options, device, source, frames));
  writer.commit();
  std::printf("sixway render: wrote %d frames, timings.json", o.frames);
  for (const std::string& f : extras) std::printf(", %s", f.c_str());
  std::printf(" to %s\n", o.out.string().c_str());
  frames.printCoverage();
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
      "neural | reference | reference-ms | reference-fit | traditional | traditional-ms | "
      "guide | guide-lit | pathtrace (default: neural when the weights exist, else reference)");
  render->add_option("--weights", o->weights, kWeightsHelp)->check(filePath());
  render->add_flag("--fp16", o->fp16, "Neural: fp16 feature maps");
  render->add_flag("--no-shadows", o->noShadows, "No obstacle shadows on the smoke");
  render->add_option("--spp", o->samples, "Pathtrace: samples per pixel (default 64)")
      ->check(CLI::Range(1, 1 << 20));
  render
      ->add_option("--orders", o->orders, "Pathtrace: scattering orders (default 64; 1 = single scattering)")
      ->check(CLI::Range(1, 100000));
  render
      ->add_option(
          "--ms-spp", o->multiple.samples,
          "reference-ms/-fit, traditional-ms: samples per traced pixel of the orders >= 2 (default 64)")
      ->check(CLI::Range(1, 1 << 20));
  render
      ->add_option(
          "--ms-downsample", o->multiple.downsample,
          "reference-ms/-fit, traditional-ms: orders >= 2 traced at 1/N of the lightmap size (default 1)")
      ->check(CLI::IsMember({1, 2, 4, 8}));
  render
      ->add_option("--fit-directions", o->fitDirections,
                   "reference-fit: light directions the six maps are fitted to, a multiple of 6 (default 36)")
      ->check(CLI::Range(1, 96));
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
