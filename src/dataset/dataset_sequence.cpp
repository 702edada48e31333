#include "dataset/dataset_sequence.h"

#include "dataset/sequence_sampler.h"
#include "io/file_access.h"
#include "io/json_text.h"
#include "render/billboard.h"
#include "render/projection.h"

namespace sixway::dataset {
namespace {

nlohmann::json vec(glm::vec3 v) {
  return {v.x, v.y, v.z};
}

nlohmann::json camerasJson(const SequenceSampler& sampler) {
  const render::Box& box = sampler.box();
  nlohmann::json cameras = nlohmann::json::array();
  for (const DatasetCamera& c : sampler.cameras()) {
    const render::ImagePlane billboard = render::billboardBounds(c.camera, box, 1.0f);
    const render::DepthRange range = render::boxDepthRange(c.camera, box);
    cameras.push_back({{"camera", c.index},
                       {"azimuth_deg", c.azimuthDeg},
                       {"elevation_deg", c.elevationDeg},
                       {"position", vec(c.camera.position)},
                       {"target", vec(box.centre())},
                       {"fov_deg", c.camera.fovYDeg},
                       {"billboard", {billboard.min.x, billboard.min.y, billboard.max.x, billboard.max.y}},
                       {"shell_depth_range", {range.near, range.far}}});
  }
  return cameras;
}

nlohmann::json samplesJson(const DatasetConfig& config, const SequencePlan& plan,
                           const SequenceSampler& sampler) {
  nlohmann::json samples = nlohmann::json::array();
  for (const DatasetCamera& c : sampler.cameras())
    for (int frame : plan.frames)
      samples.push_back({{"camera", c.index},
                         {"frame", frame},
                         {"split", sampleSplit(config, plan.sequence, c.index)},
                         {"azimuth_deg", c.azimuthDeg},
                         {"elevation_deg", c.elevationDeg}});
  return samples;
}

nlohmann::json shardMetadata(const DatasetConfig& config, const SequencePlan& plan,
                             const SequenceSampler& sampler) {
  nlohmann::json targetNames = nlohmann::json::array();
  if (config.targets.single) targetNames.push_back("single");
  if (config.targets.multiple) targetNames.push_back("multiple");
  // Version 2: the targets are named (a reader of version 1 expects `target` alone, so it refuses these);
  // version 3: so are the guide's channels, one more than before (a reader of 2 expects 3); version 4: a
  // 5th guide channel, the emission (a reader of 3 expects at most 4).
  const bool singleOnly = config.targets.single && !config.targets.multiple;
  const bool fineAlpha = config.guideChannels() >= 4;
  nlohmann::json metadata = {{"version", config.guideEmission ? 4
                                         : fineAlpha          ? 3
                                         : singleOnly         ? 1
                                                              : 2},
                             {"targets", targetNames},
                             {"sequence", plan.sequence},
                             {"attempt", plan.attempt},
                             {"lightmap_size", config.lightmapSize},
                             {"config", config.json},
                             {"scene", plan.sceneJson},
                             {"obstacle", plan.obstacle},
                             {"frame_dt", sampler.scene().time.frameDt},
                             {"stride", config.frames.stride},
                             {"cameras", camerasJson(sampler)},
                             {"samples", samplesJson(config, plan, sampler)}};
  if (!sampler.simulated()) metadata["motion"] = false;  // absent: the shard has a motion field
  if (fineAlpha) metadata["guide_channels"] = {"guide", "alpha", "depth", "alpha_fine"};
  if (config.guideEmission) metadata["guide_channels"].push_back("emission");
  return metadata;
}

}  // namespace

DatasetShard generateSequence(const gpu::Context& context, const gpu::PipelineCache& cache,
                              const DatasetConfig& config, const SequencePlan& plan,
                              const FrameProgress& progress) {
  SequenceSampler sampler(context, cache, config, plan);
  sampler.run(progress);
  DatasetShard shard;
  shard.tensors = sampler.takeTensors();
  shard.metadata = shardMetadata(config, plan, sampler);
  return shard;
}

void writeShard(const std::filesystem::path& file, const DatasetShard& shard) {
  io::removePartialsOfEndedRuns(file);
  io::writeSafetensors(file, shard.tensors, {{kShardMetadataKey, io::jsonText(shard.metadata)}});
}

nlohmann::json shardConfig(const std::filesystem::path& file) {
  const io::SafetensorsFile f = io::readSafetensors(file);
  const auto found = f.metadata.find(kShardMetadataKey);
  if (found == f.metadata.end()) return nullptr;
  const nlohmann::json metadata = nlohmann::json::parse(found->second, nullptr, false);
  return metadata.is_object() && metadata.contains("config") ? metadata["config"] : nlohmann::json();
}

}  // namespace sixway::dataset
