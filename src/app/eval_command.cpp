#include "app/eval_command.h"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/options.h"
#include "app/shipped_weights.h"
#include "eval/dataset_eval.h"
#include "eval/scene_eval.h"
#include "io/error.h"

namespace sixway::app {
namespace {

namespace fs = std::filesystem;

struct EvalOptions {
  CommonOptions common;
  fs::path dataset;
  std::vector<std::string> splits{"heldout_sequence", "heldout_camera"};
  std::string target = "single";  // the shards' targets compared with: single or multiple scattering
  eval::SceneEvalSettings scene;  // --scene, and the report, weights and --force of both paths
};

eval::DatasetEvalSettings datasetSettings(const EvalOptions& o) {
  return {o.dataset, o.scene.weights, o.scene.report, o.splits, o.target, o.scene.force};
}

void run(EvalOptions o) {
  o.scene.weights = resolveWeights(o.scene.weights);
  if (!o.dataset.empty() && !o.scene.scene.empty())
    throw io::InputError("eval", "give --dataset DIR or --scene S, not both");
  if (!o.dataset.empty()) return eval::evaluateDataset(o.common.deviceOptions(), datasetSettings(o));
  if (o.scene.scene.empty()) throw io::InputError("eval", "give --dataset DIR or --scene S");
  eval::evaluateScene(o.common.deviceOptions(), o.scene);
}

}  // namespace

void addEvalCommand(CLI::App& app) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* eval = app.add_subcommand(
      "eval", "Quality and speed: the network on a dataset, or every method on a scene's sequence");
  o->common.addTo(*eval);
  eval->add_option("--dataset", o->dataset, "Dataset directory (sixway dataset): evaluate its samples")
      ->check(directoryPath());
  eval->add_option("--split", o->splits,
                   "Dataset: splits evaluated (default heldout_sequence heldout_camera)");
  eval->add_option("--target", o->target,
                   "Dataset: the targets compared with, single (default) or multiple scattering");
  eval::SceneEvalSettings& s = o->scene;
  eval->add_option("--scene", s.scene, "Scene JSON: evaluate its sequence against the path tracer")
      ->check(filePath());
  eval->add_option("--frames", s.frames, "Scene: frames evaluated")->check(CLI::Range(1, 100000));
  eval->add_option("--out", s.out, "Scene: directory for the side-by-side strip (strip.png)")
      ->check(directoryPath());
  eval->add_option("--spp", s.samples,
                   "Scene: path-tracer samples per pixel of the ground truth (default 64)")
      ->check(CLI::Range(1, 1 << 20));
  eval->add_option("--orders", s.orders, "Scene: path-tracer scattering orders (default 64)")
      ->check(CLI::Range(1, 100000));
  eval->add_option(
          "--ms-spp", s.multipleScattering.samples,
          "Scene: reference-ms/traditional-ms, samples per traced pixel of the orders >= 2 (default 64)")
      ->check(CLI::Range(1, 1 << 20));
  eval->add_option(
          "--ms-downsample", s.multipleScattering.downsample,
          "Scene: reference-ms/traditional-ms, orders >= 2 traced at 1/N of the lightmap size (default 1)")
      ->check(CLI::IsMember({1, 2, 4, 8}));
  eval->add_flag("--ms-all-orders", s.multipleScattering.traceAllOrders,
                 "Scene: reference-ms/traditional-ms path-trace every order at full resolution (slow)");
  eval->add_option(
          "--fit-directions", s.fitDirections,
          "Scene: also measure reference-fit, the six maps fitted to the smoke lit from N directions "
          "(a multiple of 6 in 12..96, 36 suits; about N/6 times reference-ms's cost)")
      ->check(CLI::Range(0, 96));
  eval->add_option("--density-scale", s.densityScale,
                   "Scene: the smoke's extinction (optical density) x this");
  eval->add_flag(
      "--no-obstacles", [&s](int64_t) { s.obstacles = false; },
      "Scene: leave the obstacles out of every image and of the truth (they still shape the flow)");
  eval->add_flag(
      "--no-shadows", [&s](int64_t) { s.shadows = false; },
      "Scene: no obstacle shadows, in every method and in the truth");
  eval->add_option("--camera-orbit", s.cameraOrbitDeg,
                   "Scene: replace the camera path by an orbit of this many degrees per frame");
  eval->add_option("--strip-frame", s.stripFrame,
                   "Scene: frame of the strip and the equal-time study (default the last)");
  eval->add_option("--equal-time-reference-spp", s.equalTimeReferenceSamples,
                   "Scene: samples per pixel of the equal-time study's reference (default 256)")
      ->check(CLI::Range(4, 1 << 20));
  eval->add_flag(
      "--no-equal-time", [&s](int64_t) { s.equalTime = false; },
      "Scene: no equal-time study (it path-traces the strip frame up to the reference's samples)");
  eval->add_flag(
      "--truth-noise", s.truthNoise,
      "Scene: path-trace each frame twice to take the truth's noise out of its frame-to-frame change");
  eval->add_option("--weights", s.weights, kWeightsHelp)->check(filePath());
  eval->add_option("--report", s.report, "JSON report")->required()->check(filePath());
  eval->add_flag("--force", s.force, "Overwrite an existing report (and --out directory)");
  eval->callback([o] { run(*o); });
}

}  // namespace sixway::app
