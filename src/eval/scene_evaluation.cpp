#include "eval/scene_evaluation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <glm/geometric.hpp>

#include "eval/equal_time.h"
#include "eval/eval_strip.h"
#include "eval/image_detail.h"
#include "eval/obstacle_band.h"
#include "eval/scene_eval_figures.h"
#include "eval/summary_table.h"
#include "gpu/context.h"
#include "io/report.h"
#include "modes/scene_source.h"
#include "render/scene_frame.h"
#include "runtime/scene_volumes.h"

namespace sixway::eval {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// The methods measured against the path tracer, by their render-mode names (modes/render_mode.h).
// guide-lit is the guide-only baseline: the guiding map's light as all six lightmaps; reference-ms the
// axis-lit maps under full transport; reference-fit (on request) the six-way ceiling; traditional-ms the
// flipbook users bake in DCC tools.
std::vector<std::string> methodsOf(const SceneEvalSettings& s) {
  std::vector<std::string> methods{"neural", "reference", "reference-ms"};
  if (s.fitDirections > 0) methods.push_back("reference-fit");
  methods.insert(methods.end(), {"traditional", "traditional-ms", "guide-lit"});
  return methods;
}

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

modes::ModeOptions modeOptions(const SceneEvalSettings& s) {
  modes::ModeOptions options;
  options.weights = s.weights;
  options.shadows = s.shadows;
  options.pathTraceSamples = s.samples;
  options.pathTraceOrders = s.orders;
  options.multipleScattering = s.multipleScattering;
  if (s.fitDirections > 0) options.fitDirections = s.fitDirections;
  return options;
}

scene::Scene withoutObstaclesUnlessDrawn(scene::Scene scene, bool drawn) {
  if (!drawn) scene.obstacles.clear();
  return scene;
}

}  // namespace

SceneEvaluation::SceneEvaluation(const gpu::Context& context, const gpu::PipelineCache& cache,
                                 const SceneEvalSettings& settings, scene::Scene scene)
    : s_(settings),
      methodNames_(methodsOf(settings)),
      context_(context),
      cache_(cache),
      scene_(std::move(scene)),
      warmup_(scene_.render.warmupFrames),
      stripFrame_(settings.stripFrame.value_or(settings.frames - 1)),
      volumes_(modes::openSceneVolumes(context, cache, scene_, warmup_ + settings.frames,
                                       settings.scene.string())),
      simulated_(dynamic_cast<const runtime::SimulatedVolumes*>(volumes_.get())),
      renderScene_(withoutObstaclesUnlessDrawn(scene_, settings.obstacles)),
      firstCamera_(render::sceneCamera(scene_.camera, warmup_)) {
  modes::ModeOptions options = modeOptions(s_);
  for (const std::string& method : methodNames_) {
    options.mode = modes::parseRenderMode(method);
    methods_[method] = std::make_unique<modes::ModeRenderer>(context, cache, renderScene_, options);
  }
  options.mode = modes::RenderMode::PathTrace;
  truth_ = std::make_unique<modes::ModeRenderer>(context, cache, renderScene_, options);
  if (s_.truthNoise) {
    options.pathTraceSeedOffset = 0x9E3779B9u;  // far from the next frames' seeds (render.seed + frame)
    truthNoise_ = std::make_unique<modes::ModeRenderer>(context, cache, renderScene_, options);
    truthNoiseTemporal_.emplace();
  }
  if (!renderScene_.obstacles.empty())
    bandObstacles_ = std::make_unique<render::ObstacleBvh>(context, renderScene_.obstacles);
}

SceneEvaluation::~SceneEvaluation() = default;

void SceneEvaluation::run() {
  printHeading();
  started_ = Clock::now();
  for (int i = 0; i < s_.frames; ++i) evaluateFrame(i);
  const nlohmann::json figures = summary();
  io::writeReport(s_.report, report(figures));
  std::printf(
      "sixway eval: %s, frames %d-%d of the scene against the path tracer (%u spp, %d scattering orders); "
      "wrote %s\n%s",
      scene_.name.c_str(), warmup_, warmup_ + s_.frames - 1, s_.samples, s_.orders,
      s_.report.string().c_str(), summaryTable(figures, equalTime_, methodNames_).c_str());
}

void SceneEvaluation::printHeading() const {
  std::printf(
      "sixway eval: %s, %d frames after %d of warm-up, %dx%d (lightmaps %d²), path tracer %u spp, density "
      "x%g, "
      "obstacles %s, on %s\n",
      scene_.name.c_str(), s_.frames, warmup_, scene_.render.width, scene_.render.height,
      scene_.render.lightmapSize, s_.samples, s_.densityScale,
      renderScene_.obstacles.empty() ? "none drawn" : (s_.shadows ? "drawn, shadows" : "drawn, no shadows"),
      context_.properties().deviceName);
  std::fflush(stdout);
}

void SceneEvaluation::evaluateFrame(int i) {
  Frame frame = beginFrame(i);
  const modes::RenderedFrame truth = traceTruth(frame);
  const std::optional<Mask> detailMask = measureTruthNoise(frame, truth.image);
  const std::optional<Mask> band = obstacleBandOf(frame);
  Rendered rendered;
  for (const std::string& method : methodNames_)
    rendered[method] = renderMethod(method, frame, truth.image, band ? &*band : nullptr,
                                    detailMask ? &*detailMask : nullptr);
  measureLightmaps(frame);
  if (frame.i == stripFrame_ && !s_.out.empty()) writeStrip(frame, truth.image, rendered);
  if (frame.i == stripFrame_ && s_.equalTime) studyEqualTime(frame, rendered);
  endFrame(frame, truth.image, rendered);
}

SceneEvaluation::Frame SceneEvaluation::beginFrame(int i) {
  Frame frame;
  frame.i = i;
  frame.index = warmup_ + i;
  frame.volume = volumes_->volume(frame.index);
  frame.seconds = runtime::SimulatedVolumes::frameSeconds(scene_, frame.index);
  frame.camera = render::sceneCamera(scene_.camera, frame.index);
  // The view's angle away from the first frame's: where the traditional flipbook was baked.
  const float cosine = std::clamp(glm::dot(frame.camera.forward, firstCamera_.forward), -1.0f, 1.0f);
  frame.json = {{"frame", i},
                {"scene_frame", frame.index},
                {"seconds", frame.seconds},
                {"view_angle_deg", glm::degrees(std::acos(cosine))},
                {"stages_ms", nlohmann::json::object()}};
  if (simulated_) {  // a played-back VDB scene has no simulation stages
    const sim::StepTimes& sim = simulated_->frameTimes();
    const nlohmann::json simStages = {{"obstacles", sim.obstacles},
                                      {"lbm", sim.lbm},
                                      {"smoke", sim.smoke},
                                      {"forces+watchdog", sim.forces + sim.watchdog}};
    frameStages_["simulation"].push_back(simStages);
    frame.json["stages_ms"]["simulation"] = simStages;
  }
  return frame;
}

modes::RenderedFrame SceneEvaluation::traceTruth(Frame& frame) {
  const auto traced = Clock::now();
  modes::RenderedFrame truth = truth_->render(frame.index, frame.seconds, frame.volume);
  frame.json["wall_ms"]["pathtrace"] = millisecondsSince(traced);
  wallTimes_["pathtrace"].push_back(frame.json["wall_ms"]["pathtrace"].get<double>());
  frame.json["stages_ms"]["pathtrace"] = stageTimes(truth.stages);
  frameStages_["pathtrace"].push_back(frame.json["stages_ms"]["pathtrace"]);
  if (frame.i > 0) truthTemporal_.add(previous_["truth"], truth.image, previous_["truth"], truth.image);
  return truth;
}

std::optional<SceneEvaluation::Mask> SceneEvaluation::measureTruthNoise(Frame& frame,
                                                                        const io::Image& truth) {
  if (!truthNoise_) return std::nullopt;
  const modes::RenderedFrame repeat = truthNoise_->render(frame.index, frame.seconds, frame.volume);
  if (frame.i > 0) truthNoiseTemporal_->add(repeat.image, truth, previous_["truth"], truth);
  Mask mask = smokeMask(truth);
  const double signal =
      highPassEnergy(truth, mask) - 0.5 * highPassEnergyOfDifference(truth, repeat.image, mask);
  truthDetailEnergy_ += signal;
  frame.json["detail_truth_energy"] = number(signal);
  return mask;
}

std::optional<SceneEvaluation::Mask> SceneEvaluation::obstacleBandOf(Frame& frame) {
  if (!bandObstacles_) return std::nullopt;
  bandObstacles_->update(frame.seconds);
  const int width = scene_.render.width, height = scene_.render.height;
  BandSettings settings;
  settings.radius = bandRadius(height);
  settings.shadows = s_.shadows;
  settings.extinction = scene_.smoke.extinction;
  Mask band = obstacleBand(*bandObstacles_, frame.camera, render::fullFrame(frame.camera, width, height),
                           width, height, render::sceneLights(renderScene_.lights, frame.index),
                           HostDensity{frame.volume.grid, frame.volume.density->download<float>()}, settings);
  frame.json["band_pixels"] = std::count(band.begin(), band.end(), uint8_t(1));
  return band;
}

modes::RenderedFrame SceneEvaluation::renderMethod(const std::string& method, Frame& frame,
                                                   const io::Image& truth, const Mask* band,
                                                   const Mask* detailMask) {
  const auto begun = Clock::now();
  modes::RenderedFrame rendered = methods_.at(method)->render(frame.index, frame.seconds, frame.volume);
  const double wallMs = millisecondsSince(begun);
  frame.json["wall_ms"][method] = wallMs;
  wallTimes_[method].push_back(wallMs);
  const metrics::ImageError error = metrics::compareImages(rendered.image, truth, band);
  if (detailMask) {
    const double energy = highPassEnergy(rendered.image, *detailMask);
    detailEnergy_[method] += energy;
    frame.json["detail"][method] = number(energy / frame.json["detail_truth_energy"].get<double>());
  }
  imageTotal_[method] += error;
  frame.json["image"][method] = error.json();
  const metrics::ImageFaults faults = metrics::imageFaults(rendered.image);
  faultTotals_[method] += faults.total();
  frame.json["pixel_faults"][method] = faults.total();
  if (faults.total() > 0)
    std::fprintf(stderr, "sixway eval: frame %d, %s: %s\n", frame.i, method.c_str(),
                 metrics::describeFaults(faults).c_str());
  framePsnrs_[method].push_back(metrics::psnrDb(error.mseMasked()));
  frame.json["stages_ms"][method] = stageTimes(rendered.stages);
  frameStages_[method].push_back(frame.json["stages_ms"][method]);
  if (frame.i > 0) temporal_[method].add(previous_[method], rendered.image, previous_["truth"], truth);
  return rendered;
}

void SceneEvaluation::measureLightmaps(Frame& frame) {
  LightmapMetrics lightmaps;
  const io::Image predicted = methods_.at("neural")->lightmaps(),
                  reference = methods_.at("reference")->lightmaps();
  lightmaps.add(predicted.pixels, reference.pixels);
  lightmapTotal_.add(predicted.pixels, reference.pixels);
  frame.json["lightmap"] = lightmapFrame(lightmaps);
  // The same against the multiply-scattered lightmaps: what a network trained on the truth should match.
  LightmapMetrics lightmapsMs;
  const io::Image referenceMs = methods_.at("reference-ms")->lightmaps();
  lightmapsMs.add(predicted.pixels, referenceMs.pixels);
  lightmapMsTotal_.add(predicted.pixels, referenceMs.pixels);
  frame.json["lightmap_ms"] = lightmapFrame(lightmapsMs);
}

void SceneEvaluation::writeStrip(const Frame& frame, const io::Image& truth, const Rendered& rendered) {
  const std::vector<std::string> panels =
      writeEvalStrip(s_.out / "strip.png", truth,
                     {{"neural", &rendered.at("neural").image},
                      {"reference", &rendered.at("reference").image},
                      {"traditional-ms", &rendered.at("traditional-ms").image}});
  strip_ = {{"file", (s_.out / "strip.png").string()}, {"frame", frame.i}, {"panels", panels}};
}

void SceneEvaluation::studyEqualTime(const Frame& frame, const Rendered& rendered) {
  EqualTimeSettings equal;
  equal.budgetMs = median(wallTimes_["neural"]);
  equal.samples = s_.equalTimeReferenceSamples;
  equal.orders = s_.orders;
  equalTime_ = equalTimeStudy(context_, cache_, renderScene_, frame.index, frame.volume, equal,
                              &rendered.at("neural").image);
  equalTime_["frame"] = frame.i;
}

void SceneEvaluation::endFrame(Frame& frame, const io::Image& truth, Rendered& rendered) {
  frames_.push_back(frame.json);
  for (auto& [method, r] : rendered) previous_[method] = std::move(r.image);
  previous_["truth"] = truth;
  printProgress(frame);
}

void SceneEvaluation::printProgress(const Frame& frame) const {
  const double elapsed = std::chrono::duration<double>(Clock::now() - started_).count();
  std::printf(
      "  frame %d/%d (%.0f° from the baked view): lightmaps %.2f dB; images vs path tracer:", frame.i + 1,
      s_.frames, frame.json["view_angle_deg"].get<double>(), orNan(frame.json["lightmap"]["psnr_masked_db"]));
  for (const std::string& method : methodNames_)
    std::printf(" %s %.2f", method.c_str(), orNan(frame.json["image"][method]["psnr_masked_db"]));
  std::printf(" dB; %.0f s elapsed, ETA %.0f s\n", elapsed,
              elapsed / (frame.i + 1) * (s_.frames - frame.i - 1));
  std::fflush(stdout);
}

nlohmann::json SceneEvaluation::summary() {
  nlohmann::json summary = {{"lightmap", lightmapTotal_.summary()},
                            {"lightmap_ms", lightmapMsTotal_.summary()}};
  for (const std::string& method : methodNames_) {
    nlohmann::json image = imageTotal_[method].json();  // pooled over the frames' pixels
    const std::vector<double>& psnrs = framePsnrs_[method];
    const auto finite = std::count_if(psnrs.begin(), psnrs.end(), [](double v) { return std::isfinite(v); });
    double sum = 0;
    for (double v : psnrs) sum += std::isfinite(v) ? v : 0.0;
    image["mean_frame_psnr_masked_db"] = number(finite ? sum / double(finite) : NAN);
    image["pixel_faults"] = faultTotals_[method];
    summary["image"][method] = image;
  }
  for (const auto& [method, stages] : frameStages_) summary["median_ms"][method] = medianTimes(stages);
  for (const auto& [method, times] : wallTimes_) summary["median_ms"][method]["wall_ms"] = median(times);
  summary["temporal"] = temporalSummary(temporal_, truthTemporal_, truthNoiseTemporal_);
  summary["detail"] = nullptr;
  if (truthNoise_) {
    summary["detail"] = {{"truth_energy", number(truthDetailEnergy_)}, {"sigma_px", kDetailSigma}};
    for (const std::string& method : methodNames_)
      summary["detail"]["methods"][method] = number(detailEnergy_[method] / truthDetailEnergy_);
  }
  return summary;
}

nlohmann::json SceneEvaluation::report(const nlohmann::json& summary) const {
  const reference::MultipleScattering& ms = s_.multipleScattering;
  return {{"scene", fs::absolute(s_.scene).string()},
          {"device", context_.properties().deviceName},
          {"driver", std::string(context_.driver().driverInfo)},
          {"weights", fs::absolute(s_.weights).string()},
          {"frames", s_.frames},
          {"warmup_frames", warmup_},
          {"size", {scene_.render.width, scene_.render.height}},
          {"lightmap_size", scene_.render.lightmapSize},
          {"pathtrace_spp", s_.samples},
          {"pathtrace_orders", s_.orders},
          {"multiple_scattering",
           {{"samples_per_pixel", ms.samples},
            {"orders", ms.maxOrders},
            {"downsample", ms.traceAllOrders ? 1 : ms.downsample},
            {"all_orders_traced", ms.traceAllOrders}}},
          {"density_scale", s_.densityScale},
          {"obstacles_drawn", !renderScene_.obstacles.empty()},
          {"obstacle_count", scene_.obstacles.size()},
          {"source", modes::describeSource(*volumes_)},
          {"shadows", !renderScene_.obstacles.empty() && s_.shadows},
          {"band_radius_px",
           bandObstacles_ ? nlohmann::json(bandRadius(scene_.render.height)) : nlohmann::json(nullptr)},
          {"camera_orbit_deg_per_frame", s_.cameraOrbitDeg ? number(*s_.cameraOrbitDeg) : nullptr},
          {"methods", methodNames_},
          {"summary", summary},
          {"equal_time", equalTime_},
          {"strip", strip_.is_null() ? nlohmann::json(nullptr) : strip_},
          {"per_frame", frames_}};
}

}  // namespace sixway::eval
