#include "eval/dataset_eval.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <span>
#include <stdexcept>

#include "eval/lightmap_metrics.h"
#include "eval/shard_network.h"
#include "io/error.h"
#include "io/file_access.h"
#include "io/json_reader.h"
#include "io/report.h"
#include "io/safetensors.h"
#include "reference/scattering.h"
#include "runtime/internal.h"
#include "runtime/network_weights.h"
#include "scene/scene.h"

namespace sixway::eval {
namespace {

namespace fs = std::filesystem;

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

// A shard and its sixway.dataset description.
struct Shard {
  io::SafetensorsFile tensors;
  nlohmann::json description;
  int lightmapSize = 0;
};

Shard readShard(const fs::path& path) {
  Shard shard{io::readSafetensors(path), nullptr, 0};
  const auto meta = shard.tensors.metadata.find("sixway.dataset");
  if (meta == shard.tensors.metadata.end()) throw io::InputError(path.string(), "no sixway.dataset metadata");
  shard.description = io::parseJsonText(meta->second, path.string() + ": sixway.dataset");
  if (!shard.description.is_object() || !shard.description.contains("samples") ||
      !shard.description.contains("lightmap_size"))
    throw io::InputError(path.string(), "sixway.dataset metadata is not a dataset description");
  shard.lightmapSize = shard.description["lightmap_size"].get<int>();
  return shard;
}

// The name of the shards' target tensor that --target asks for, required of `shard`.
std::string targetTensor(const DatasetEvalSettings& s, const fs::path& path, const Shard& shard) {
  const std::string name = reference::parseScattering(s.target, "--target") == reference::Scattering::Single
                               ? "target"
                               : "target_ms";
  if (!shard.tensors.contains(name))
    throw io::InputError(path.string(), "no tensor " + name + " (the dataset config's \"targets\" " +
                                            "did not include " + s.target + " scattering)");
  return name;
}

// Every sample of the splits asked for through the network, against the target, into `metrics`.
class DatasetEvaluation {
 public:
  DatasetEvaluation(const gpu::Context& context, const gpu::PipelineCache& cache,
                    const DatasetEvalSettings& s, const io::SafetensorsFile& weights)
      : context_(context),
        cache_(cache),
        s_(s),
        weights_(weights),
        splits_(s.splits.begin(), s.splits.end()) {}

  void evaluateShard(const fs::path& path);
  nlohmann::json report() const;

 private:
  void evaluateSamples(const fs::path& path, const Shard& shard, const std::string& target);

  const gpu::Context& context_;
  const gpu::PipelineCache& cache_;
  const DatasetEvalSettings& s_;
  const io::SafetensorsFile& weights_;
  const std::set<std::string> splits_;
  std::unique_ptr<ShardNetwork> network_;  // on the first shard's lightmap size
  std::map<std::string, LightmapMetrics> metrics_;
  std::vector<double> inferenceMs_;
};

void DatasetEvaluation::evaluateShard(const fs::path& path) {
  const Shard shard = readShard(path);
  if (!network_) {
    network_ = std::make_unique<ShardNetwork>(context_, cache_, weights_, shard.lightmapSize,
                                              sceneAlbedo(path, shard.description));
  } else if (shard.lightmapSize != network_->size()) {
    throw io::InputError(path.string(), "lightmap size " + std::to_string(shard.lightmapSize) +
                                            " differs from the first shard's " +
                                            std::to_string(network_->size()));
  }
  evaluateSamples(path, shard, targetTensor(s_, path, shard));
  std::printf("  %s: %zu samples\n", path.filename().string().c_str(), shard.description["samples"].size());
  std::fflush(stdout);
}

void DatasetEvaluation::evaluateSamples(const fs::path& path, const Shard& shard, const std::string& target) {
  const std::vector<float> guides = shard.tensors.at("guide").toFloat(),
                           targets = shard.tensors.at(target).toFloat();
  const int64_t pixels = int64_t(network_->size()) * network_->size();
  const nlohmann::json& samples = shard.description["samples"];
  const int channels = guideChannels(path, shard.description, network_->graph());
  network_->setAlbedo(sceneAlbedo(path, shard.description));
  if (int64_t(guides.size()) != int64_t(samples.size()) * channels * pixels ||
      int64_t(targets.size()) != int64_t(samples.size()) * 8 * pixels)
    throw io::InputError(path.string(),
                         "tensor shapes do not match its " + std::to_string(samples.size()) + " samples");
  for (int64_t n = 0; n < int64_t(samples.size()); ++n) {
    const std::string split = samples[size_t(n)].value("split", "");
    if (!splits_.count(split)) continue;
    const io::Image lightmaps = network_->infer(interleaved(guides, n, channels, pixels), channels);
    inferenceMs_.push_back(network_->lastMilliseconds());
    metrics_[split].add(lightmaps.pixels, interleaved(targets, n, 8, pixels));
  }
}

nlohmann::json DatasetEvaluation::report() const {
  nlohmann::json report = {{"weights", fs::absolute(s_.weights).string()},
                           {"dataset", fs::absolute(s_.dataset).string()},
                           {"target", s_.target},
                           {"device", context_.properties().deviceName},
                           {"lightmap_size", network_ ? network_->size() : 0}};
  for (const auto& [split, m] : metrics_) {
    report["splits"][split] = m.summary();
    const nlohmann::json s = m.summary();
    std::printf("sixway eval: %-17s %5llu samples, PSNR %.2f dB masked (%.2f full)\n", split.c_str(),
                (unsigned long long)m.samples(),
                s["psnr_masked_db"].is_null() ? NAN : s["psnr_masked_db"].get<double>(),
                s["psnr_full_db"].is_null() ? NAN : s["psnr_full_db"].get<double>());
  }
  if (metrics_.empty()) throw io::InputError(s_.dataset.string(), "has no samples in the splits asked for");
  std::vector<double> inferenceMs = inferenceMs_;
  std::sort(inferenceMs.begin(), inferenceMs.end());
  report["inference_ms_median"] = inferenceMs[inferenceMs.size() / 2];
  return report;
}

}  // namespace

void evaluateDataset(const DeviceOptions& device, const DatasetEvalSettings& s) {
  io::requireWritableFile(s.report, s.force);
  const std::vector<fs::path> shards = shardFiles(s.dataset);
  const io::SafetensorsFile weights = runtime::readWeights(s.weights);

  const Device gpuDevice(device);
  DatasetEvaluation evaluation(runtime::Access::context(gpuDevice), runtime::Access::pipelineCache(gpuDevice),
                               s, weights);
  for (const fs::path& shard : shards) evaluation.evaluateShard(shard);
  io::writeReport(s.report, evaluation.report());
  if (gpuDevice.validationMessages() > 0)
    throw std::runtime_error(std::to_string(gpuDevice.validationMessages()) + " validation messages");
}

}  // namespace sixway::eval
