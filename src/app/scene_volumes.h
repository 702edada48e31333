#pragma once
// `sixway bake --scene`: the volumes of a scene's simulation, frame after frame. This is the one place where
// the bake meets the simulation (issue #3).
#include <memory>

#include "io/scene.h"
#include "render/volume_sequence.h"

namespace sixway::gpu {
class Context;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::app {

// Frame i is the smoke after i + 1 frames of simulation (t = (i + 1) · time.frame_dt); `frames` frames.
std::unique_ptr<render::VolumeSequence> simulatedVolumes(const gpu::Context& context,
                                                         const gpu::PipelineCache& cache,
                                                         const io::Scene& scene, int frames);

}  // namespace sixway::app
