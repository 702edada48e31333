#include "dataset/dataset_sequence.h"

#include <algorithm>
#include <cstring>
#include <glm/gtc/packing.hpp>
#include <optional>

#include "dataset/motion_field.h"
#include "gpu/context.h"
#include "gpu/image.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "io/file_access.h"
#include "io/json_text.h"
#include "modes/scene_source.h"
#include "reference/scattered_lightmaps.h"
#include "render/billboard.h"
#include "render/guiding_map.h"
#include "render/projection.h"
#include "runtime/scene_volumes.h"

namespace sixway::dataset {
namespace {

constexpr int kTargetChannels = 8, kMotionChannels = 2;

// The seed of one sample's multiple-scattering trace: the scene's render.seed mixed with the sample's
// sequence, frame and camera, so a shard regenerates bit for bit and no two samples share their noise.
uint32_t sampleSeed(uint32_t seed, int sequence, int frame, int camera) {
  uint32_t h = seed;
  for (uint32_t v : {uint32_t(sequence), uint32_t(frame), uint32_t(camera)}) {
    h ^= v + 0x9E3779B9u + (h << 6) + (h >> 2);  // boost::hash_combine's mixing
  }
  return h;
}

// An F16 tensor [samples, channels, size, size], filled sample by sample from interleaved float images.
class PlanarTensor {
 public:
  PlanarTensor(std::string name, int samples, int channels, int size)
      : name_(std::move(name)),
        channels_(channels),
        size_(size),
        bytes_(size_t(samples) * channels * size * size * 2, 0) {}

  // `image` holds at least channels_ interleaved channels per pixel (`stride` values per pixel).
  void set(int sample, const std::vector<float>& image, int stride) {
    const size_t plane = size_t(size_) * size_;
    std::vector<float> planar(plane * channels_);
    for (int c = 0; c < channels_; ++c)
      for (size_t i = 0; i < plane; ++i) planar[c * plane + i] = image[i * stride + c];
    const io::Tensor half = io::Tensor::fromFloat("", io::DType::F16, {int64_t(planar.size())}, planar);
    std::memcpy(bytes_.data() + size_t(sample) * half.bytes.size(), half.bytes.data(), half.bytes.size());
  }

  io::Tensor take(int samples) {
    return {name_, io::DType::F16, {samples, channels_, size_, size_}, std::move(bytes_)};
  }

 private:
  std::string name_;
  int channels_, size_;
  std::vector<uint8_t> bytes_;
};

std::vector<float> downloadHalfTexels(const gpu::Image& image) {
  const std::vector<uint16_t> texels = image.download<uint16_t>();
  std::vector<float> values(texels.size());
  for (size_t i = 0; i < texels.size(); ++i) values[i] = glm::unpackHalf1x16(texels[i]);
  return values;
}

// The guide's pixels with the emission as a 5th channel (interleaved).
std::vector<float> appendChannel(const std::vector<float>& rgba, const std::vector<float>& channel) {
  std::vector<float> out(channel.size() * 5);
  for (size_t i = 0; i < channel.size(); ++i) {
    std::copy_n(&rgba[i * 4], 4, &out[i * 5]);
    out[i * 5 + 4] = channel[i];
  }
  return out;
}

nlohmann::json vec(glm::vec3 v) {
  return {v.x, v.y, v.z};
}

}  // namespace

DatasetShard generateSequence(const gpu::Context& context, const gpu::PipelineCache& cache,
                              const DatasetConfig& config, const SequencePlan& plan,
                              const FrameProgress& progress) {
  scene::Scene scene = plan.scene;
  const int size = config.lightmapSize;
  const int lastFrame = plan.frames.back();
  const std::unique_ptr<render::VolumeSequence> volumes =
      modes::openSceneVolumes(context, cache, scene, lastFrame + 1, config.file.string());
  // A played-back VDB scene has no velocity: its samples get no motion field (zero, "motion": false).
  const auto* simulated = dynamic_cast<const runtime::SimulatedVolumes*>(volumes.get());
  const render::Box box = volumes->bounds();
  const std::vector<DatasetCamera> cameras = datasetCameras(config, box);
  const int samplesPerCamera = int(plan.frames.size());
  const int samples = int(cameras.size()) * samplesPerCamera;

  render::GuideSettings guideSettings = render::GuideSettings::fromScene(scene);
  guideSettings.emission = config.guideEmission;
  render::GuidingMap guiding(context, cache, guideSettings);
  const gpu::Image guide(context, guiding.imageDesc());
  std::optional<gpu::Image> emission;
  if (config.guideEmission) emission.emplace(context, guiding.emissionDesc());
  const gpu::Image* emissionImage = emission ? &*emission : nullptr;
  dataset::MotionField motion(context, cache, uint32_t(size));
  reference::ScatteredLightmaps baker(context, cache);
  reference::BakeSettings bake;
  bake.width = bake.height = size;
  // The smoke travels over the interval between two samples: stride frames of steps, at the lattice velocity
  // (cells per step) the simulation's macro buffer holds.
  const float metresPerVelocityUnit =
      simulated ? simulated->simulation().units().cellSize *
                      float(simulated->simulation().units().stepsPerFrame * config.frames.stride)
                : 0.0f;
  const render::VolumeGrid velocityGrid{scene.grid.size, scene.grid.origin, scene.grid.cellSize};

  PlanarTensor guides("guide", samples, config.guideChannels(), size),
      targets("target", config.targets.single ? samples : 0, kTargetChannels, size),
      targetsMs("target_ms", config.targets.multiple ? samples : 0, kTargetChannels, size),
      motions("motion", samples, kMotionChannels, size);
  gpu::Sequence realtime(context);
  bool recorded = false;
  size_t next = 0;  // the next sampled frame
  for (int frame = 0; frame <= lastFrame; ++frame) {
    const render::Volume volume = volumes->volume(frame);
    if (frame == plan.frames[next]) {
      if (!recorded) {  // the volume's buffers stay the same from frame to frame
        guiding.record(realtime, volume, guide, emissionImage);
        if (simulated) motion.record(realtime, guide, simulated->simulation().lbm().macro(), velocityGrid);
        realtime.finish();
        recorded = true;
      }
      for (const DatasetCamera& c : cameras) {
        const render::ImagePlane billboard = render::billboardBounds(c.camera, box, 1.0f);
        const render::DepthRange shellRange = render::boxDepthRange(c.camera, box);
        guiding.update(c.camera, billboard, shellRange, scene.smoke, uint32_t(frame));
        if (simulated) motion.update(c.camera, billboard, shellRange, metresPerVelocityUnit);
        realtime.submit();
        const int sample = c.index * samplesPerCamera + int(next);
        if (emission)
          guides.set(sample, appendChannel(downloadHalfTexels(guide), emission->download<float>()), 5);
        else
          guides.set(sample, downloadHalfTexels(guide), 4);
        if (config.targets.multiple) {
          reference::MultipleScattering ms = config.targets.multipleScattering;
          ms.seed = sampleSeed(scene.render.seed, plan.sequence, frame, c.index);
          targetsMs.set(
              sample,
              baker.bake(volume, scene.smoke, c.camera, billboard, bake, reference::Scattering::Multiple, ms)
                  .pixels,
              kTargetChannels);
          if (config.targets.single) targets.set(sample, baker.singleScattering().pixels, kTargetChannels);
        } else {
          targets.set(
              sample,
              baker.bake(volume, scene.smoke, c.camera, billboard, bake, reference::Scattering::Single)
                  .pixels,
              kTargetChannels);
        }
        // The first sample of a camera has no previous one to move from.
        if (next > 0 && simulated) motions.set(sample, motion.download().pixels, kMotionChannels);
      }
      ++next;
    }
    if (progress) progress(frame + 1, lastFrame + 1);
  }

  nlohmann::json cameraJson = nlohmann::json::array(), sampleJson = nlohmann::json::array();
  for (const DatasetCamera& c : cameras) {
    const render::ImagePlane billboard = render::billboardBounds(c.camera, box, 1.0f);
    const render::DepthRange range = render::boxDepthRange(c.camera, box);
    cameraJson.push_back({{"camera", c.index},
                          {"azimuth_deg", c.azimuthDeg},
                          {"elevation_deg", c.elevationDeg},
                          {"position", vec(c.camera.position)},
                          {"target", vec(box.centre())},
                          {"fov_deg", c.camera.fovYDeg},
                          {"billboard", {billboard.min.x, billboard.min.y, billboard.max.x, billboard.max.y}},
                          {"shell_depth_range", {range.near, range.far}}});
    for (int frame : plan.frames)
      sampleJson.push_back({{"camera", c.index},
                            {"frame", frame},
                            {"split", sampleSplit(config, plan.sequence, c.index)},
                            {"azimuth_deg", c.azimuthDeg},
                            {"elevation_deg", c.elevationDeg}});
  }
  DatasetShard shard;
  shard.tensors = {guides.take(samples)};
  nlohmann::json targetNames = nlohmann::json::array();
  if (config.targets.single) {
    shard.tensors.push_back(targets.take(samples));
    targetNames.push_back("single");
  }
  if (config.targets.multiple) {
    shard.tensors.push_back(targetsMs.take(samples));
    targetNames.push_back("multiple");
  }
  shard.tensors.push_back(motions.take(samples));
  // Version 2: the targets are named (a reader of version 1 expects `target` alone, so it refuses these);
  // version 3: so are the guide's channels, one more than before (a reader of 2 expects 3); version 4: a
  // 5th guide channel, the emission (a reader of 3 expects at most 4).
  const bool singleOnly = config.targets.single && !config.targets.multiple;
  const bool fineAlpha = config.guideChannels() >= 4;
  shard.metadata = {{"version", config.guideEmission ? 4
                                : fineAlpha          ? 3
                                : singleOnly         ? 1
                                                     : 2},
                    {"targets", targetNames},
                    {"sequence", plan.sequence},
                    {"attempt", plan.attempt},
                    {"lightmap_size", size},
                    {"config", config.json},
                    {"scene", plan.sceneJson},
                    {"obstacle", plan.obstacle},
                    {"frame_dt", scene.time.frameDt},
                    {"stride", config.frames.stride},
                    {"cameras", cameraJson},
                    {"samples", sampleJson}};
  if (!simulated) shard.metadata["motion"] = false;  // absent: the shard has a motion field
  if (fineAlpha) shard.metadata["guide_channels"] = {"guide", "alpha", "depth", "alpha_fine"};
  if (config.guideEmission) shard.metadata["guide_channels"].push_back("emission");
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
