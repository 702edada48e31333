#include "eval/scene_eval.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "eval/equal_time.h"
#include "eval/eval_strip.h"
#include "eval/image_detail.h"
#include "eval/lightmap_metrics.h"
#include "eval/obstacle_band.h"
#include "eval/summary_table.h"
#include "eval/temporal_change.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "io/error.h"
#include "io/file_access.h"
#include "io/report.h"
#include "metrics/image_metrics.h"
#include "modes/mode_renderer.h"
#include "modes/scene_source.h"
#include "render/camera.h"
#include "render/obstacle_bvh.h"
#include "render/scene_frame.h"
#include "runtime/internal.h"
#include "runtime/network_weights.h"
#include "runtime/scene_volumes.h"
#include "scene/scene.h"

namespace sixway::eval {
namespace {

namespace fs = std::filesystem;

// The methods measured against the path tracer, by their render-mode names (modes/render_mode.h).
// guide-lit is the guide-only baseline: the guiding map's light as all six lightmaps; reference-ms the
// six-way ceiling under full transport (multiply-scattered lightmaps); traditional-ms the flipbook users bake
// in DCC tools.
const std::vector<std::string> kMethods{"neural",      "reference",      "reference-ms",
                                        "traditional", "traditional-ms", "guide-lit"};

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

nlohmann::json number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

double orNan(const nlohmann::json& v) {
  return v.is_number() ? v.get<double>() : NAN;
}

// Per stage and in total, each stage's time summed over its repeats in the frame (e.g. several bake passes).
nlohmann::json stageTimes(const std::vector<gpu::StageTime>& stages) {
  nlohmann::json json = nlohmann::json::object();
  for (const gpu::StageTime& s : stages) json[s.name] = json.value(s.name, 0.0) + s.milliseconds;
  return json;
}

double totalMs(const nlohmann::json& stages) {
  double total = 0;
  for (const auto& [name, ms] : stages.items()) total += ms.get<double>();
  return total;
}

// Medians over the frames of each stage and of the total, from the per-frame "stages_ms" of one method.
nlohmann::json medianTimes(const std::vector<nlohmann::json>& frames) {
  std::map<std::string, std::vector<double>> perStage;
  std::vector<double> totals;
  for (const nlohmann::json& f : frames) {
    for (const auto& [name, ms] : f.items()) perStage[name].push_back(ms.get<double>());
    totals.push_back(totalMs(f));
  }
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& [name, values] : perStage) stages[name] = median(values);
  return {{"stages_ms", stages}, {"total_ms", median(totals)}};
}

// The lightmap figures of one frame, with the MSEs the PSNRs stand for.
nlohmann::json lightmapFrame(const LightmapMetrics& m) {
  const nlohmann::json s = m.summary();
  nlohmann::json out = {{"psnr_masked_db", s["psnr_masked_db"]}, {"psnr_full_db", s["psnr_full_db"]}};
  out["mse_masked"] = number(std::pow(10.0, -orNan(s["psnr_masked_db"]) / 10.0));
  out["mse_full"] = number(std::pow(10.0, -orNan(s["psnr_full_db"]) / 10.0));
  return out;
}

// Each method's frame-to-frame change next to the truth's (the target: within 20% of it); the truth's with
// its Monte Carlo noise taken out where that was measured (--truth-noise). Null for a single frame.
nlohmann::json temporalSummary(const std::map<std::string, TemporalChange>& methods,
                               const TemporalChange& truth, const std::optional<TemporalChange>& noise) {
  if (truth.values == 0) return nullptr;
  nlohmann::json truthJson = temporalJson(truth);
  const double truthRms = noise ? rmsWithoutNoise(truth, *noise) : truth.rms();
  truthJson["noise_rms"] = noise ? number(noise->rms()) : nlohmann::json(nullptr);
  truthJson["rms_without_noise"] = noise ? number(truthRms) : nlohmann::json(nullptr);
  nlohmann::json json = {{"truth", truthJson}, {"truth_noise_removed", noise.has_value()}};
  for (const auto& [method, change] : methods) {
    nlohmann::json m = temporalJson(change);
    m["rms_ratio"] = number(truthRms > 0 ? change.rms() / truthRms : NAN);
    json["methods"][method] = m;
  }
  return json;
}

// The scene as evaluated: the density scale on the extinction (σ_t = extinction · density, so scaling one
// scales the other for every renderer), and the camera path replaced when asked.
scene::Scene evaluatedScene(const SceneEvalSettings& s) {
  scene::Scene scene = scene::loadScene(s.scene);
  scene.smoke.extinction *= s.densityScale;
  if (s.cameraOrbitDeg) scene.camera.path = scene::CameraOrbit{*s.cameraOrbitDeg};
  return scene;
}

void check(const SceneEvalSettings& s) {
  if (s.frames < 1) throw io::InputError("--frames", "give at least 1 frame with --scene");
  if (!(s.densityScale > 0.0f) || !std::isfinite(s.densityScale))
    throw io::InputError("--density-scale", "must be a positive number");
  if (s.stripFrame && (*s.stripFrame < 0 || *s.stripFrame >= s.frames))
    throw io::InputError("--strip-frame", "frame " + std::to_string(*s.stripFrame) + " is outside 0.." +
                                              std::to_string(s.frames - 1));
  runtime::readWeights(s.weights);  // a missing or malformed file fails before any work
}

}  // namespace

void evaluateScene(const DeviceOptions& device, const SceneEvalSettings& s) {
  check(s);
  scene::Scene scene = evaluatedScene(s);
  io::requireWritableFile(s.report, s.force);
  if (!s.out.empty()) io::requireWritableDirectory(s.out, s.force);
  const int stripFrame = s.stripFrame.value_or(s.frames - 1);
  // The scene's warm-up frames (render.warmup_frames) are simulated but not evaluated, as `sixway render`
  // skips them: evaluated frame i is scene frame warmup + i (its smoke, camera and lights).
  const int warmup = scene.render.warmupFrames;

  const Device gpuDevice(device);
  const gpu::Context& context = runtime::Access::context(gpuDevice);
  const gpu::PipelineCache& cache = runtime::Access::pipelineCache(gpuDevice);
  const std::unique_ptr<render::VolumeSequence> volumes =
      modes::openSceneVolumes(context, cache, scene, warmup + s.frames, s.scene.string());
  const auto* simulated = dynamic_cast<const runtime::SimulatedVolumes*>(volumes.get());
  // What the renderers see: the obstacles, unless left out (--no-obstacles).
  scene::Scene renderScene = scene;
  if (!s.obstacles) renderScene.obstacles.clear();
  modes::ModeOptions options;
  options.weights = s.weights;
  options.shadows = s.shadows;
  options.pathTraceSamples = s.samples;
  options.pathTraceOrders = s.orders;
  options.multipleScattering = s.multipleScattering;
  std::map<std::string, std::unique_ptr<modes::ModeRenderer>> renderers;
  for (const std::string& method : kMethods) {
    options.mode = modes::parseRenderMode(method);
    renderers[method] = std::make_unique<modes::ModeRenderer>(context, cache, renderScene, options);
  }
  options.mode = modes::RenderMode::PathTrace;
  modes::ModeRenderer truthRenderer(context, cache, renderScene, options);
  std::unique_ptr<modes::ModeRenderer> truthNoiseRenderer;  // the same frames with other noise
  if (s.truthNoise) {
    options.pathTraceSeedOffset = 0x9E3779B9u;  // far from the next frames' seeds (render.seed + frame)
    truthNoiseRenderer = std::make_unique<modes::ModeRenderer>(context, cache, renderScene, options);
  }
  // The band around the obstacles (obstacle_band.h), where the images draw them.
  std::unique_ptr<render::ObstacleBvh> bandObstacles;
  if (!renderScene.obstacles.empty())
    bandObstacles = std::make_unique<render::ObstacleBvh>(context, renderScene.obstacles);
  if (!s.out.empty()) fs::create_directories(s.out);
  std::printf(
      "sixway eval: %s, %d frames after %d of warm-up, %dx%d (lightmaps %d²), path tracer %u spp, density "
      "x%g, "
      "obstacles %s, on %s\n",
      scene.name.c_str(), s.frames, warmup, scene.render.width, scene.render.height,
      scene.render.lightmapSize, s.samples, s.densityScale,
      renderScene.obstacles.empty() ? "none drawn" : (s.shadows ? "drawn, shadows" : "drawn, no shadows"),
      context.properties().deviceName);
  std::fflush(stdout);

  const render::Camera firstCamera = render::sceneCamera(scene.camera, warmup);
  LightmapMetrics lightmapTotal, lightmapMsTotal;
  std::map<std::string, metrics::ImageError> imageTotal;
  std::map<std::string, std::vector<double>> framePsnrs;
  std::map<std::string, std::vector<nlohmann::json>> frameStages;
  std::map<std::string, std::vector<double>>
      wallTimes;  // per method, per frame: render() on the host's clock
  nlohmann::json frames = nlohmann::json::array(), equalTime, strip;
  std::map<std::string, TemporalChange> temporal;
  TemporalChange truthTemporal;
  std::optional<TemporalChange> truthNoise;
  if (s.truthNoise) truthNoise.emplace();
  std::map<std::string, io::Image> previous;  // the last frame of every method, "truth" included
  // High-pass energies summed over the frames (image_detail.h): each method's, and the truth's without its
  // noise.
  std::map<std::string, double> detailEnergy;
  double truthDetailEnergy = 0;
  std::map<std::string, uint64_t>
      faultTotals;  // pixels no renderer should make (metrics::imageFaults), per method
  const auto started = std::chrono::steady_clock::now();
  for (int i = 0; i < s.frames; ++i) {
    const int index = warmup + i;
    const render::Volume volume = volumes->volume(index);
    const double seconds = runtime::SimulatedVolumes::frameSeconds(scene, index);
    // The view's angle away from the first frame's: where the traditional flipbook was baked.
    const render::Camera camera = render::sceneCamera(scene.camera, index);
    const float cosine = std::clamp(glm::dot(camera.forward, firstCamera.forward), -1.0f, 1.0f);
    nlohmann::json frame = {{"frame", i},
                            {"scene_frame", index},
                            {"seconds", seconds},
                            {"view_angle_deg", glm::degrees(std::acos(cosine))},
                            {"stages_ms", nlohmann::json::object()}};
    if (simulated) {  // a played-back VDB scene has no simulation stages
      const sim::StepTimes& sim = simulated->frameTimes();
      const nlohmann::json simStages = {{"obstacles", sim.obstacles},
                                        {"lbm", sim.lbm},
                                        {"smoke", sim.smoke},
                                        {"forces+watchdog", sim.forces + sim.watchdog}};
      frameStages["simulation"].push_back(simStages);
      frame["stages_ms"]["simulation"] = simStages;
    }

    const auto traced = std::chrono::steady_clock::now();
    const modes::RenderedFrame truth = truthRenderer.render(index, seconds, volume);
    frame["wall_ms"]["pathtrace"] =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - traced).count();
    wallTimes["pathtrace"].push_back(frame["wall_ms"]["pathtrace"].get<double>());
    frame["stages_ms"]["pathtrace"] = stageTimes(truth.stages);
    frameStages["pathtrace"].push_back(frame["stages_ms"]["pathtrace"]);
    if (i > 0) truthTemporal.add(previous["truth"], truth.image, previous["truth"], truth.image);
    std::optional<std::vector<uint8_t>> detailMask;
    if (truthNoiseRenderer) {
      const modes::RenderedFrame repeat = truthNoiseRenderer->render(index, seconds, volume);
      if (i > 0) truthNoise->add(repeat.image, truth.image, previous["truth"], truth.image);
      detailMask = smokeMask(truth.image);
      const double signal = highPassEnergy(truth.image, *detailMask) -
                            0.5 * highPassEnergyOfDifference(truth.image, repeat.image, *detailMask);
      truthDetailEnergy += signal;
      frame["detail_truth_energy"] = number(signal);
    }
    std::optional<std::vector<uint8_t>> band;
    if (bandObstacles) {
      bandObstacles->update(seconds);
      const int width = scene.render.width, height = scene.render.height;
      BandSettings settings;
      settings.radius = bandRadius(height);
      settings.shadows = s.shadows;
      settings.extinction = scene.smoke.extinction;
      band = obstacleBand(*bandObstacles, camera, render::fullFrame(camera, width, height), width, height,
                          render::sceneLights(renderScene.lights, index),
                          HostDensity{volume.grid, volume.density->download<float>()}, settings);
      frame["band_pixels"] = std::count(band->begin(), band->end(), uint8_t(1));
    }
    std::map<std::string, modes::RenderedFrame> rendered;
    for (const std::string& method : kMethods) {
      const auto begun = std::chrono::steady_clock::now();
      rendered[method] = renderers[method]->render(index, seconds, volume);
      const double wallMs =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begun).count();
      frame["wall_ms"][method] = wallMs;
      wallTimes[method].push_back(wallMs);
      const metrics::ImageError error =
          metrics::compareImages(rendered[method].image, truth.image, band ? &*band : nullptr);
      if (detailMask) {
        const double energy = highPassEnergy(rendered[method].image, *detailMask);
        detailEnergy[method] += energy;
        frame["detail"][method] = number(energy / frame["detail_truth_energy"].get<double>());
      }
      imageTotal[method] += error;
      frame["image"][method] = error.json();
      const metrics::ImageFaults faults = metrics::imageFaults(rendered[method].image);
      faultTotals[method] += faults.total();
      frame["pixel_faults"][method] = faults.total();
      if (faults.total() > 0)
        std::fprintf(stderr, "sixway eval: frame %d, %s: %s\n", i, method.c_str(),
                     metrics::describeFaults(faults).c_str());
      framePsnrs[method].push_back(metrics::psnrDb(error.mseMasked()));
      frame["stages_ms"][method] = stageTimes(rendered[method].stages);
      frameStages[method].push_back(frame["stages_ms"][method]);
      if (i > 0)
        temporal[method].add(previous[method], rendered[method].image, previous["truth"], truth.image);
    }
    LightmapMetrics lightmaps;
    const io::Image predicted = renderers["neural"]->lightmaps(),
                    reference = renderers["reference"]->lightmaps();
    lightmaps.add(predicted.pixels, reference.pixels);
    lightmapTotal.add(predicted.pixels, reference.pixels);
    frame["lightmap"] = lightmapFrame(lightmaps);
    // The same against the multiply-scattered lightmaps: what a network trained on the truth should match.
    LightmapMetrics lightmapsMs;
    const io::Image referenceMs = renderers["reference-ms"]->lightmaps();
    lightmapsMs.add(predicted.pixels, referenceMs.pixels);
    lightmapMsTotal.add(predicted.pixels, referenceMs.pixels);
    frame["lightmap_ms"] = lightmapFrame(lightmapsMs);

    if (i == stripFrame && !s.out.empty()) {
      const std::vector<std::string> panels =
          writeEvalStrip(s.out / "strip.png", truth.image,
                         {{"neural", &rendered["neural"].image},
                          {"reference", &rendered["reference"].image},
                          {"traditional-ms", &rendered["traditional-ms"].image}});
      strip = {{"file", (s.out / "strip.png").string()}, {"frame", i}, {"panels", panels}};
    }
    if (i == stripFrame && s.equalTime) {
      EqualTimeSettings equal;
      equal.budgetMs = median(wallTimes["neural"]);
      equal.samples = s.equalTimeReferenceSamples;
      equal.orders = s.orders;
      equalTime =
          equalTimeStudy(context, cache, renderScene, index, volume, equal, &rendered["neural"].image);
      equalTime["frame"] = i;
    }
    frames.push_back(frame);
    for (auto& [method, r] : rendered) previous[method] = std::move(r.image);
    previous["truth"] = truth.image;

    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    std::printf("  frame %d/%d (%.0f° from the baked view): lightmaps %.2f dB; images vs path tracer:", i + 1,
                s.frames, frame["view_angle_deg"].get<double>(), orNan(frame["lightmap"]["psnr_masked_db"]));
    for (const std::string& method : kMethods)
      std::printf(" %s %.2f", method.c_str(), orNan(frame["image"][method]["psnr_masked_db"]));
    std::printf(" dB; %.0f s elapsed, ETA %.0f s\n", elapsed, elapsed / (i + 1) * (s.frames - i - 1));
    std::fflush(stdout);
  }

  nlohmann::json summary = {{"lightmap", lightmapTotal.summary()},
                            {"lightmap_ms", lightmapMsTotal.summary()}};
  for (const std::string& method : kMethods) {
    nlohmann::json image = imageTotal[method].json();  // pooled over the frames' pixels
    const std::vector<double>& psnrs = framePsnrs[method];
    const auto finite = std::count_if(psnrs.begin(), psnrs.end(), [](double v) { return std::isfinite(v); });
    double sum = 0;
    for (double v : psnrs) sum += std::isfinite(v) ? v : 0.0;
    image["mean_frame_psnr_masked_db"] = number(finite ? sum / double(finite) : NAN);
    image["pixel_faults"] = faultTotals[method];
    summary["image"][method] = image;
  }
  for (const auto& [method, stages] : frameStages) summary["median_ms"][method] = medianTimes(stages);
  for (const auto& [method, times] : wallTimes) summary["median_ms"][method]["wall_ms"] = median(times);
  summary["temporal"] = temporalSummary(temporal, truthTemporal, truthNoise);
  summary["detail"] = nullptr;
  if (truthNoiseRenderer) {
    summary["detail"] = {{"truth_energy", number(truthDetailEnergy)}, {"sigma_px", kDetailSigma}};
    for (const std::string& method : kMethods)
      summary["detail"]["methods"][method] = number(detailEnergy[method] / truthDetailEnergy);
  }

  nlohmann::json report = {
      {"scene", fs::absolute(s.scene).string()},
      {"device", context.properties().deviceName},
      {"driver", std::string(context.driver().driverInfo)},
      {"weights", fs::absolute(s.weights).string()},
      {"frames", s.frames},
      {"warmup_frames", warmup},
      {"size", {scene.render.width, scene.render.height}},
      {"lightmap_size", scene.render.lightmapSize},
      {"pathtrace_spp", s.samples},
      {"pathtrace_orders", s.orders},
      {"multiple_scattering",
       {{"samples_per_pixel", s.multipleScattering.samples},
        {"orders", s.multipleScattering.maxOrders},
        {"downsample", s.multipleScattering.traceAllOrders ? 1 : s.multipleScattering.downsample},
        {"all_orders_traced", s.multipleScattering.traceAllOrders}}},
      {"density_scale", s.densityScale},
      {"obstacles_drawn", !renderScene.obstacles.empty()},
      {"obstacle_count", scene.obstacles.size()},
      {"source", modes::describeSource(*volumes)},
      {"shadows", !renderScene.obstacles.empty() && s.shadows},
      {"band_radius_px",
       bandObstacles ? nlohmann::json(bandRadius(scene.render.height)) : nlohmann::json(nullptr)},
      {"camera_orbit_deg_per_frame", s.cameraOrbitDeg ? number(*s.cameraOrbitDeg) : nullptr},
      {"methods", kMethods},
      {"summary", summary},
      {"equal_time", equalTime},
      {"strip", strip.is_null() ? nlohmann::json(nullptr) : strip},
      {"per_frame", frames}};
  io::writeReport(s.report, report);
  std::printf(
      "sixway eval: %s, frames %d-%d of the scene against the path tracer (%u spp, %d scattering orders); "
      "wrote %s\n%s",
      scene.name.c_str(), warmup, warmup + s.frames - 1, s.samples, s.orders, s.report.string().c_str(),
      summaryTable(summary, equalTime, kMethods).c_str());
  if (gpuDevice.validationMessages() > 0)
    throw std::runtime_error(std::to_string(gpuDevice.validationMessages()) + " validation messages");
}

}  // namespace sixway::eval
