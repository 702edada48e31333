#pragma once
// The samples of one sequence of `sixway dataset` (dataset_sequence.h): its smoke frame by frame, and per
// sampled frame and camera the guiding map, the reference baker's eight channels and the motion field,
// collected as the shard's F16 tensors.
#include <memory>
#include <vector>

#include "dataset/dataset_config.h"
#include "dataset/dataset_sequence.h"
#include "dataset/motion_field.h"
#include "dataset/planar_tensor.h"
#include "gpu/image.h"
#include "gpu/sequence.h"
#include "reference/lightmap_baker.h"
#include "reference/scattered_lightmaps.h"
#include "render/guiding_map.h"
#include "render/volume_sequence.h"
#include "scene/scene.h"

namespace sixway::runtime {
class SimulatedVolumes;
}

namespace sixway::dataset {

class SequenceSampler {
 public:
  // Opens the plan's smoke (a VDB scene's `grid` becomes its playback lattice) and every pass it is sampled
  // with.
  SequenceSampler(const gpu::Context& context, const gpu::PipelineCache& cache, const DatasetConfig& config,
                  const SequencePlan& plan);
  ~SequenceSampler();

  // Every frame of the sequence, the sampled ones from every camera.
  void run(const FrameProgress& progress);
  // The tensors: guide, the targets asked for (single, then multiple scattering), motion.
  std::vector<io::Tensor> takeTensors();

  const scene::Scene& scene() const { return scene_; }
  const render::Box& box() const { return box_; }
  const std::vector<DatasetCamera>& cameras() const { return cameras_; }
  // A played-back VDB scene has no velocity: its samples get no motion field (zero).
  bool simulated() const { return simulated_ != nullptr; }

 private:
  void recordOnce(const render::Volume& volume);
  void sampleCamera(const DatasetCamera& c, int frame, int sampled, const render::Volume& volume);
  void bakeTargets(const DatasetCamera& c, int frame, int sample, const render::Volume& volume,
                   const render::ImagePlane& billboard);

  const DatasetConfig& config_;
  const SequencePlan& plan_;
  scene::Scene scene_;
  const int size_;
  const int lastFrame_;
  const std::unique_ptr<render::VolumeSequence> volumes_;
  const runtime::SimulatedVolumes* simulated_;
  const render::Box box_;
  const std::vector<DatasetCamera> cameras_;
  const int samplesPerCamera_;
  const int samples_;
  render::GuidingMap guiding_;
  const gpu::Image guide_;
  const std::unique_ptr<gpu::Image> emission_;  // with the guide's emission channel
  MotionField motion_;
  reference::ScatteredLightmaps baker_;
  reference::BakeSettings bake_;
  // The smoke travels over the interval between two samples: stride frames of steps, at the lattice velocity
  // (cells per step) the simulation's macro buffer holds.
  const float metresPerVelocityUnit_;
  const render::VolumeGrid velocityGrid_;
  PlanarTensor guides_, targets_, targetsMs_, motions_;
  gpu::Sequence realtime_;
  bool recorded_ = false;
};

}  // namespace sixway::dataset
