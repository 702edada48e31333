#include "dataset/sequence_sampler.h"

#include <algorithm>
#include <glm/gtc/packing.hpp>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "modes/scene_source.h"
#include "render/billboard.h"
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

render::GuideSettings guideSettings(const scene::Scene& scene, const DatasetConfig& config) {
  render::GuideSettings settings = render::GuideSettings::fromScene(scene);
  settings.emission = config.guideEmission;
  return settings;
}

std::unique_ptr<gpu::Image> emissionImage(const gpu::Context& context, const render::GuidingMap& guiding,
                                          const DatasetConfig& config) {
  return config.guideEmission ? std::make_unique<gpu::Image>(context, guiding.emissionDesc()) : nullptr;
}

reference::BakeSettings bakeSettings(int size) {
  reference::BakeSettings bake;
  bake.width = bake.height = size;
  return bake;
}

float metresPerVelocityUnit(const runtime::SimulatedVolumes* simulated, const DatasetConfig& config) {
  if (!simulated) return 0.0f;
  const sim::LatticeUnits& units = simulated->simulation().units();
  return units.cellSize * float(units.stepsPerFrame * config.frames.stride);
}

}  // namespace

SequenceSampler::SequenceSampler(const gpu::Context& context, const gpu::PipelineCache& cache,
                                 const DatasetConfig& config, const SequencePlan& plan)
    : config_(config),
      plan_(plan),
      scene_(plan.scene),
      size_(config.lightmapSize),
      lastFrame_(plan.frames.back()),
      volumes_(modes::openSceneVolumes(context, cache, scene_, lastFrame_ + 1, config.file.string())),
      simulated_(dynamic_cast<const runtime::SimulatedVolumes*>(volumes_.get())),
      box_(volumes_->bounds()),
      cameras_(datasetCameras(config, box_)),
      samplesPerCamera_(int(plan.frames.size())),
      samples_(int(cameras_.size()) * samplesPerCamera_),
      guiding_(context, cache, guideSettings(scene_, config)),
      guide_(context, guiding_.imageDesc()),
      emission_(emissionImage(context, guiding_, config)),
      motion_(context, cache, uint32_t(size_)),
      baker_(context, cache),
      bake_(bakeSettings(size_)),
      metresPerVelocityUnit_(metresPerVelocityUnit(simulated_, config)),
      velocityGrid_{scene_.grid.size, scene_.grid.origin, scene_.grid.cellSize},
      guides_("guide", samples_, config.guideChannels(), size_),
      targets_("target", config.targets.single ? samples_ : 0, kTargetChannels, size_),
      targetsMs_("target_ms", config.targets.multiple ? samples_ : 0, kTargetChannels, size_),
      motions_("motion", samples_, kMotionChannels, size_),
      realtime_(context) {}

SequenceSampler::~SequenceSampler() = default;

void SequenceSampler::run(const FrameProgress& progress) {
  size_t next = 0;  // the next sampled frame
  for (int frame = 0; frame <= lastFrame_; ++frame) {
    const render::Volume volume = volumes_->volume(frame);
    if (frame == plan_.frames[next]) {
      recordOnce(volume);
      for (const DatasetCamera& c : cameras_) sampleCamera(c, frame, int(next), volume);
      ++next;
    }
    if (progress) progress(frame + 1, lastFrame_ + 1);
  }
}

// The volume's buffers stay the same from frame to frame: the guide and motion passes are recorded once.
void SequenceSampler::recordOnce(const render::Volume& volume) {
  if (recorded_) return;
  guiding_.record(realtime_, volume, guide_, emission_.get());
  if (simulated_) motion_.record(realtime_, guide_, simulated_->simulation().lbm().macro(), velocityGrid_);
  realtime_.finish();
  recorded_ = true;
}

void SequenceSampler::sampleCamera(const DatasetCamera& c, int frame, int sampled,
                                   const render::Volume& volume) {
  const render::ImagePlane billboard = render::billboardBounds(c.camera, box_, 1.0f);
  const render::DepthRange shellRange = render::boxDepthRange(c.camera, box_);
  guiding_.update(c.camera, billboard, shellRange, scene_.smoke, uint32_t(frame));
  if (simulated_) motion_.update(c.camera, billboard, shellRange, metresPerVelocityUnit_);
  realtime_.submit();
  const int sample = c.index * samplesPerCamera_ + sampled;
  if (emission_)
    guides_.set(sample, appendChannel(downloadHalfTexels(guide_), emission_->download<float>()), 5);
  else
    guides_.set(sample, downloadHalfTexels(guide_), 4);
  bakeTargets(c, frame, sample, volume, billboard);
  // The first sample of a camera has no previous one to move from.
  if (sampled > 0 && simulated_) motions_.set(sample, motion_.download().pixels, kMotionChannels);
}

void SequenceSampler::bakeTargets(const DatasetCamera& c, int frame, int sample, const render::Volume& volume,
                                  const render::ImagePlane& billboard) {
  if (config_.targets.multiple) {
    reference::MultipleScattering ms = config_.targets.multipleScattering;
    ms.seed = sampleSeed(scene_.render.seed, plan_.sequence, frame, c.index);
    targetsMs_.set(
        sample,
        baker_.bake(volume, scene_.smoke, c.camera, billboard, bake_, reference::Scattering::Multiple, ms)
            .pixels,
        kTargetChannels);
    if (config_.targets.single) targets_.set(sample, baker_.singleScattering().pixels, kTargetChannels);
  } else {
    targets_.set(
        sample,
        baker_.bake(volume, scene_.smoke, c.camera, billboard, bake_, reference::Scattering::Single).pixels,
        kTargetChannels);
  }
}

std::vector<io::Tensor> SequenceSampler::takeTensors() {
  std::vector<io::Tensor> tensors = {guides_.take(samples_)};
  if (config_.targets.single) tensors.push_back(targets_.take(samples_));
  if (config_.targets.multiple) tensors.push_back(targetsMs_.take(samples_));
  tensors.push_back(motions_.take(samples_));
  return tensors;
}

}  // namespace sixway::dataset
