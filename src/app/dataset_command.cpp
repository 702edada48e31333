#include "app/dataset_command.h"

#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "app/dataset_progress.h"
#include "app/options.h"
#include "dataset/dataset_config.h"
#include "dataset/dataset_sequence.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "io/error.h"
#include "io/file_access.h"
#include "io/json_reader.h"
#include "io/report.h"
#include "render/obstacle_meshes.h"
#include "runtime/internal.h"
#include "sim/watchdog.h"

namespace sixway::app {
namespace {

namespace fs = std::filesystem;

struct DatasetOptions {
  CommonOptions common;
  fs::path config, out;
  std::string shard;
  bool force = false;
};

// DIR/dataset.json: what every worker of the dataset shares (the same file whichever writes it).
nlohmann::json datasetIndex(const dataset::DatasetConfig& config) {
  const dataset::SequencePlan first = dataset::planSequence(config, 0);
  nlohmann::json cameras = nlohmann::json::array(), shards = nlohmann::json::array();
  for (const dataset::DatasetCamera& c : dataset::datasetCameras(config, render::domainBox(first.scene.grid)))
    cameras.push_back(
        {{"camera", c.index}, {"azimuth_deg", c.azimuthDeg}, {"elevation_deg", c.elevationDeg}});
  for (int s = 0; s < config.sequenceCount(); ++s) shards.push_back(dataset::shardFileName(s));
  return {{"version", 1},
          {"config", config.json},
          {"sequences", config.sequenceCount()},
          {"vdb_sequences", config.vdbScenes.size()},
          {"lightmap_size", config.lightmapSize},
          {"cameras", cameras},
          {"heldout", {{"sequences", config.heldoutSequences}, {"cameras", config.heldoutCameras}}},
          {"shards", shards}};
}

// The config recorded in an existing dataset.json.
nlohmann::json indexConfig(const fs::path& file) {
  const std::vector<uint8_t> bytes = io::readFileBytes(file);
  const nlohmann::json index = io::parseJsonText(
      std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), file.string());
  return index.is_object() && index.contains("config") ? index["config"] : nlohmann::json();
}

[[noreturn]] void otherConfig(const fs::path& file) {
  throw io::InputError(file.string(), "was made from another config; pass --force to overwrite it");
}

// The scene of a sequence that could not be made goes next to the shards (with absolute mesh paths), so that
// `sixway sim --scene` reproduces the failure.
[[noreturn]] void failed(const DatasetOptions& o, const dataset::DatasetConfig& config,
                         const dataset::SequencePlan& plan, const std::string& failure) {
  char name[48];
  std::snprintf(name, sizeof(name), "failed_sequence_%05d.json", plan.sequence);
  io::writeReport(o.out / name, dataset::standaloneScene(config, plan));
  throw std::runtime_error(o.config.string() + ": " + failure + "; its scene is " + (o.out / name).string());
}

// The sequences this worker makes. A shard made from this config is complete (files are renamed into place
// once written), so it is kept and counted: a worker that is run again resumes; one made from another config
// stops the run unless --force.
struct WorkerPlan {
  std::vector<dataset::SequencePlan> plans;
  int kept = 0;
};

WorkerPlan planWorker(const DatasetOptions& o, const dataset::DatasetConfig& config,
                      const dataset::ShardSelection& selection) {
  WorkerPlan work;
  for (int s = 0; s < config.sequenceCount(); ++s) {
    if (!selection.contains(s)) continue;
    dataset::SequencePlan plan = dataset::planSequence(config, s);
    const fs::path file = o.out / dataset::shardFileName(s);
    if (!o.force && fs::exists(file)) {
      if (dataset::shardConfig(file) != config.json) otherConfig(file);
      ++work.kept;
      continue;
    }
    work.plans.push_back(std::move(plan));
  }
  return work;
}

void printHeading(const DatasetOptions& o, const dataset::DatasetConfig& config,
                  const dataset::ShardSelection& selection, const WorkerPlan& work,
                  const gpu::Context& context) {
  std::printf(
      "sixway dataset: %s, sequences %d..%d step %d of %d: %zu to make, %d already made; %d cameras, "
      "%d samples per camera, %d² lightmaps, on %s\n",
      o.config.string().c_str(), selection.index, config.sequenceCount() - 1, selection.count,
      config.sequenceCount(), work.plans.size(), work.kept, config.cameraCount(), config.frames.count,
      config.lightmapSize, context.properties().deviceName);
  std::fflush(stdout);
}

// The sequence of `plan`, its variations drawn again when they make a flow the lattice cannot hold (a fixed
// number of times); one that cannot be made ends the run, its scene left beside the shards.
dataset::DatasetShard makeSequence(const gpu::Context& context, const gpu::PipelineCache& cache,
                                   const DatasetOptions& o, const dataset::DatasetConfig& config,
                                   dataset::SequencePlan& plan, int position, DatasetProgress& progress) {
  for (;;) {
    try {
      return dataset::generateSequence(context, cache, config, plan, [&](int done, int total) {
        progress.frameDone(plan.sequence, position, done, total);
      });
    } catch (const sim::WatchdogError& e) {
      const std::string failure = "sequence " + std::to_string(plan.sequence) + " (attempt " +
                                  std::to_string(plan.attempt + 1) + " of " +
                                  std::to_string(config.attempts) + "): " + e.what();
      if (plan.attempt + 1 >= config.attempts) {
        progress.endLine();
        failed(o, config, plan, failure);
      }
      progress.note(failure + "; drawing its variations again");
      plan = dataset::planSequence(config, plan.sequence, plan.attempt + 1);
      progress.addFrames(plan.frames.back() + 1);
    } catch (const std::exception& e) {
      progress.endLine();
      failed(o, config, plan, "sequence " + std::to_string(plan.sequence) + ": " + e.what());
    }
  }
}

void writeSequence(const DatasetOptions& o, const dataset::SequencePlan& plan,
                   const dataset::DatasetShard& shard, std::map<std::string, int>& splits,
                   DatasetProgress& progress) {
  const std::string name = dataset::shardFileName(plan.sequence);
  dataset::writeShard(o.out / name, shard);
  for (const nlohmann::json& sample : shard.metadata["samples"]) ++splits[sample["split"].get<std::string>()];
  progress.note("wrote " + name + " (" + std::to_string(shard.metadata["samples"].size()) +
                " samples, obstacle " + plan.obstacle + ")");
}

void run(const DatasetOptions& o) {
  const dataset::DatasetConfig config = dataset::loadDatasetConfig(o.config);
  const dataset::ShardSelection selection =
      o.shard.empty() ? dataset::ShardSelection{} : dataset::parseShardSelection(o.shard);
  if (fs::exists(o.out) && !fs::is_directory(o.out))
    throw io::InputError(o.out.string(), "exists and is not a directory");
  // Everything is checked before the first frame: every scene of this worker, and that nothing made from
  // another config would be overwritten.
  const nlohmann::json index = datasetIndex(config);
  const fs::path indexFile = o.out / "dataset.json";
  if (!o.force && fs::exists(indexFile) && indexConfig(indexFile) != config.json) otherConfig(indexFile);
  const WorkerPlan work = planWorker(o, config, selection);

  const Device device(o.common.deviceOptions());
  const gpu::Context& context = runtime::Access::context(device);
  const gpu::PipelineCache& cache = runtime::Access::pipelineCache(device);
  fs::create_directories(o.out);
  io::writeReport(indexFile, index);
  long totalFrames = 0;
  for (const dataset::SequencePlan& plan : work.plans) totalFrames += plan.frames.back() + 1;
  printHeading(o, config, selection, work, context);
  DatasetProgress progress(int(work.plans.size()), totalFrames);
  std::map<std::string, int> splits;
  for (size_t i = 0; i < work.plans.size(); ++i) {
    dataset::SequencePlan plan = work.plans[i];
    const dataset::DatasetShard shard = makeSequence(context, cache, o, config, plan, int(i) + 1, progress);
    writeSequence(o, plan, shard, splits, progress);
  }
  std::string counts;
  for (const auto& [split, n] : splits)
    counts += (counts.empty() ? "" : ", ") + split + " " + std::to_string(n);
  std::printf("sixway dataset: wrote %zu shards (%s) to %s in %s\n", work.plans.size(),
              counts.empty() ? "no samples" : counts.c_str(), o.out.string().c_str(),
              formatDuration(progress.elapsedSeconds()).c_str());
  requireNoValidationMessages(device);
}

}  // namespace

void addDatasetCommand(CLI::App& app) {
  auto o = std::make_shared<DatasetOptions>();
  CLI::App* dataset =
      app.add_subcommand("dataset", "Training pairs: guiding map → reference lightmaps, per sequence");
  o->common.addTo(*dataset);
  dataset->add_option("--config", o->config, "Dataset config JSON (docs/dataset-format.md)")
      ->required()
      ->check(filePath());
  dataset->add_option("--out", o->out, "Output directory (shared by the workers of one dataset)")
      ->required()
      ->check(directoryPath());
  dataset->add_option("--shard", o->shard, "I/N: make the sequences S with S mod N = I");
  dataset->add_flag("--force", o->force, "Remake shards that exist, and overwrite those of another config");
  dataset->callback([o] { run(*o); });
}

}  // namespace sixway::app
