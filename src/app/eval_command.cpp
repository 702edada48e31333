#include "app/eval_command.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "app/options.h"
#include "app/shipped_weights.h"
#include "eval/lightmap_metrics.h"
#include "eval/scene_eval.h"
#include "gpu/context.h"
#include "gpu/image.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "io/error.h"
#include "io/file_access.h"
#include "io/json_reader.h"
#include "io/report.h"
#include "io/safetensors.h"
#include "nn/network.h"
#include "render/lightmap_images.h"
#include "runtime/internal.h"
#include "runtime/network_weights.h"
#include "scene/scene.h"

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

// The shards that the directory's dataset.json lists, every one required (a missing shard would silently drop
// its sequences, and with them perhaps a whole split); without a dataset.json, the shard files present.
std::vector<fs::path> shardFiles(const fs::path& directory) {
  if (!fs::is_directory(directory)) throw io::InputError(directory.string(), "no such dataset directory");
  std::vector<fs::path> shards;
  if (const fs::path indexFile = directory / "dataset.json"; fs::exists(indexFile)) {
    const std::vector<uint8_t> bytes = io::readFileBytes(indexFile);
    const nlohmann::json index = io::parseJsonText(
        std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), indexFile.string());
    const nlohmann::json* listed = index.is_object() && index.contains("shards") ? &index["shards"] : nullptr;
    if (!listed || !listed->is_array() || listed->empty())
      throw io::InputError(indexFile.string(), "shards: expected the list of shard files");
    for (const nlohmann::json& name : *listed) {
      if (!name.is_string() || fs::path(name.get<std::string>()).has_parent_path())
        throw io::InputError(indexFile.string(), "shards: expected file names");
      const fs::path shard = directory / name.get<std::string>();
      if (!fs::is_regular_file(shard))
        throw io::InputError(shard.string(), "missing: dataset.json lists " + std::to_string(listed->size()) +
                                                 " shards (is `sixway dataset` still making it?)");
      shards.push_back(shard);
    }
    return shards;
  }
  for (const auto& entry : fs::directory_iterator(directory)) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with("shard_") && entry.path().extension() == ".safetensors")
      shards.push_back(entry.path());
  }
  if (shards.empty()) throw io::InputError(directory.string(), "holds no shard_*.safetensors files");
  std::sort(shards.begin(), shards.end());
  return shards;
}

// Sample n of an NCHW tensor of `channels` channels, pixel-interleaved (as io::Image and the metrics hold
// it).
std::vector<float> interleaved(const std::vector<float>& nchw, int64_t n, int channels, int64_t pixels) {
  std::vector<float> out(size_t(pixels) * channels);
  const float* sample = nchw.data() + n * channels * pixels;
  for (int64_t p = 0; p < pixels; ++p)
    for (int c = 0; c < channels; ++c) out[size_t(p) * channels + c] = sample[c * pixels + p];
  return out;
}

// Whether a shard's scene emits (smoke.emission.intensity > 0): its guide's emission is not zero.
bool sceneEmits(const nlohmann::json& description) {
  const nlohmann::json intensity =
      description.value(nlohmann::json::json_pointer("/scene/smoke/emission/intensity"), nlohmann::json(0.0));
  return intensity.is_number() && intensity.get<double>() > 0.0;
}

// The guide channels of a shard (3, 4 with the fine alpha: version 3, 5 with the emission: version 4),
// checked against what the network reads: a network that reads the fine alpha needs it, of the step it was
// trained on; one that reads the emission needs it unless the scene emits nothing (then it is zero).
int guideChannels(const fs::path& shard, const nlohmann::json& description, const nn::Graph& graph) {
  const int channels = description.contains("guide_channels") ? int(description["guide_channels"].size()) : 3;
  if (channels < 3 || channels > nn::kMaxGuideChannels)
    throw io::InputError(shard.string(), "guide_channels must name 3 to 5 channels");
  if (graph.nodes.front().guideChannels > nn::kGuideImageChannels && channels == nn::kGuideImageChannels &&
      sceneEmits(description))
    throw io::InputError(shard.string(),
                         "the network reads the guide's emission, which this shard of an "
                         "emissive scene lacks (the dataset config's \"guide\": "
                         "{\"emission\": true})");
  const float wanted = graph.nodes.front().guideAlphaStepVoxels;
  if (wanted == 0.0f) return channels;
  // Absent (or under a scene that is not an object): no fine alpha.
  const nlohmann::json step = description.value(
      nlohmann::json::json_pointer("/scene/render/guide_alpha_step_voxels"), nlohmann::json(0.0));
  if (!step.is_number())
    throw io::InputError(shard.string(), "scene.render.guide_alpha_step_voxels is not a number");
  const float held = channels >= 4 ? step.get<float>() : 0.0f;
  if (held != wanted)
    throw io::InputError(shard.string(), "the network reads a fine alpha of step " + io::show(wanted) +
                                             " voxels; the shard's guide has " +
                                             (held > 0.0f ? "step " + io::show(held) : std::string("none")) +
                                             " (the dataset config's \"guide\")");
  return channels;
}

// The smoke's albedo of a shard's scene (absent: a scene's default), which a network may read.
float sceneAlbedo(const fs::path& shard, const nlohmann::json& description) {
  const nlohmann::json albedo = description.value(nlohmann::json::json_pointer("/scene/smoke/albedo"),
                                                  nlohmann::json(scene::Smoke{}.albedo));
  if (!albedo.is_number() || !(albedo.get<float>() >= 0.0f && albedo.get<float>() <= 1.0f))
    throw io::InputError(shard.string(), "scene.smoke.albedo must be a number in [0, 1]");
  return albedo.get<float>();
}

void evaluateDataset(const EvalOptions& o) {
  io::requireWritableFile(o.scene.report, o.scene.force);
  const std::vector<fs::path> shards = shardFiles(o.dataset);
  const fs::path weightsPath = o.scene.weights;
  const io::SafetensorsFile weights = runtime::readWeights(weightsPath);
  const std::set<std::string> splits(o.splits.begin(), o.splits.end());

  const Device device(o.common.deviceOptions());
  const gpu::Context& context = runtime::Access::context(device);
  const gpu::PipelineCache& cache = runtime::Access::pipelineCache(device);
  std::unique_ptr<nn::Network> network;
  std::unique_ptr<render::LightmapImages> lightmaps;
  std::unique_ptr<gpu::Image> guide, emission;
  std::unique_ptr<gpu::Sequence> sequence;
  int size = 0;
  std::map<std::string, eval::LightmapMetrics> metrics;
  std::vector<double> inferenceMs;
  for (const fs::path& shardPath : shards) {
    const io::SafetensorsFile shard = io::readSafetensors(shardPath);
    const auto meta = shard.metadata.find("sixway.dataset");
    if (meta == shard.metadata.end()) throw io::InputError(shardPath.string(), "no sixway.dataset metadata");
    const nlohmann::json description =
        io::parseJsonText(meta->second, shardPath.string() + ": sixway.dataset");
    if (!description.is_object() || !description.contains("samples") ||
        !description.contains("lightmap_size"))
      throw io::InputError(shardPath.string(), "sixway.dataset metadata is not a dataset description");
    const int shardSize = description["lightmap_size"].get<int>();
    if (!network) {
      size = shardSize;
      nn::NetworkOptions options;
      options.albedo = sceneAlbedo(shardPath, description);
      network =
          std::make_unique<nn::Network>(context, cache, weights, uint32_t(size), uint32_t(size), options);
      lightmaps = std::make_unique<render::LightmapImages>(context, uint32_t(size), uint32_t(size));
      guide = std::make_unique<gpu::Image>(
          context, gpu::ImageDesc{uint32_t(size), uint32_t(size), 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                                  VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "guide"});
      if (network->graph().nodes.front().guideChannels > nn::kGuideImageChannels)
        emission = std::make_unique<gpu::Image>(
            context,
            gpu::ImageDesc{uint32_t(size), uint32_t(size), 1, VK_FORMAT_R32_SFLOAT,
                           VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "guide emission"});
      sequence = std::make_unique<gpu::Sequence>(context);
      sequence->beginStage("network");
      network->record(*sequence, {*guide, emission.get()}, lightmaps->a, lightmaps->b);
      sequence->endStage();
      sequence->finish();
    } else if (shardSize != size) {
      throw io::InputError(shardPath.string(), "lightmap size " + std::to_string(shardSize) +
                                                   " differs from the first shard's " + std::to_string(size));
    }
    const std::string targetName =
        reference::parseScattering(o.target, "--target") == reference::Scattering::Single ? "target"
                                                                                          : "target_ms";
    if (!shard.contains(targetName))
      throw io::InputError(shardPath.string(), "no tensor " + targetName +
                                                   " (the dataset config's \"targets\" " +
                                                   "did not include " + o.target + " scattering)");
    const std::vector<float> guides = shard.at("guide").toFloat(), targets = shard.at(targetName).toFloat();
    const int64_t pixels = int64_t(size) * size;
    const nlohmann::json& samples = description["samples"];
    const int channels = guideChannels(shardPath, description, network->graph());
    network->setAlbedo(sceneAlbedo(shardPath, description));
    if (int64_t(guides.size()) != int64_t(samples.size()) * channels * pixels ||
        int64_t(targets.size()) != int64_t(samples.size()) * 8 * pixels)
      throw io::InputError(shardPath.string(),
                           "tensor shapes do not match its " + std::to_string(samples.size()) + " samples");
    for (int64_t n = 0; n < int64_t(samples.size()); ++n) {
      const std::string split = samples[size_t(n)].value("split", "");
      if (!splits.count(split)) continue;
      const std::vector<float> g = interleaved(guides, n, channels, pixels);
      std::vector<float> rgba(size_t(pixels) * 4, 0.0f), emitted(size_t(pixels), 0.0f);
      for (int64_t p = 0; p < pixels; ++p) {
        for (int c = 0; c < std::min(channels, nn::kGuideImageChannels); ++c)
          rgba[size_t(p) * 4 + c] = g[size_t(p) * channels + c];
        if (channels > nn::kGuideImageChannels) emitted[size_t(p)] = g[size_t(p) * channels + 4];
      }
      guide->upload(std::as_bytes(std::span(rgba)));
      if (emission) emission->upload(std::as_bytes(std::span(emitted)));
      sequence->submit();
      inferenceMs.push_back(sequence->stageTimes().front().milliseconds);
      metrics[split].add(lightmaps->download().pixels, interleaved(targets, n, 8, pixels));
    }
    std::printf("  %s: %zu samples\n", shardPath.filename().string().c_str(), samples.size());
    std::fflush(stdout);
  }

  nlohmann::json report = {{"weights", fs::absolute(weightsPath).string()},
                           {"dataset", fs::absolute(o.dataset).string()},
                           {"target", o.target},
                           {"device", context.properties().deviceName},
                           {"lightmap_size", size}};
  for (const auto& [split, m] : metrics) {
    report["splits"][split] = m.summary();
    const nlohmann::json s = m.summary();
    std::printf("sixway eval: %-17s %5llu samples, PSNR %.2f dB masked (%.2f full)\n", split.c_str(),
                (unsigned long long)m.samples(),
                s["psnr_masked_db"].is_null() ? NAN : s["psnr_masked_db"].get<double>(),
                s["psnr_full_db"].is_null() ? NAN : s["psnr_full_db"].get<double>());
  }
  if (metrics.empty()) throw io::InputError(o.dataset.string(), "has no samples in the splits asked for");
  std::sort(inferenceMs.begin(), inferenceMs.end());
  report["inference_ms_median"] = inferenceMs[inferenceMs.size() / 2];
  io::writeReport(o.scene.report, report);
  requireNoValidationMessages(device);
}

void run(EvalOptions o) {
  o.scene.weights = resolveWeights(o.scene.weights);
  if (!o.dataset.empty() && !o.scene.scene.empty())
    throw io::InputError("eval", "give --dataset DIR or --scene S, not both");
  if (!o.dataset.empty()) return evaluateDataset(o);
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
