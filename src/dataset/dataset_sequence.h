#pragma once
// One sequence of `sixway dataset` (docs/dataset-format.md): its scene simulated frame by frame, and per
// sampled frame and camera the guiding map, the reference baker's eight channels and the motion field, kept
// as the tensors and metadata of one shard file.
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <vector>

#include "dataset/dataset_config.h"
#include "io/safetensors.h"

namespace sixway::gpu {
class Context;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::dataset {

struct DatasetShard {
  std::vector<io::Tensor> tensors;  // guide [N,3 or 4,H,W], target [N,8,H,W], motion [N,2,H,W], F16
  nlohmann::json metadata;          // the value of the header's "sixway.dataset"
};

// Called after each simulated frame with the frames done and the frames the sequence simulates.
using FrameProgress = std::function<void(int done, int total)>;

DatasetShard generateSequence(const gpu::Context& context, const gpu::PipelineCache& cache,
                              const DatasetConfig& config, const SequencePlan& plan,
                              const FrameProgress& progress = {});

// Written under a temporary name and renamed (io::writeSafetensors), after removing the temporary files of
// `file` that killed runs left (io::removePartialsOfEndedRuns).
void writeShard(const std::filesystem::path& file, const DatasetShard& shard);

// The metadata key of a shard, and the "config" a shard file was made from (null when the file has no
// dataset metadata). Throws io::InputError for a file that is not a safetensors file.
constexpr const char* kShardMetadataKey = "sixway.dataset";
nlohmann::json shardConfig(const std::filesystem::path& file);

}  // namespace sixway::dataset
