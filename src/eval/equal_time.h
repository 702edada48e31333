#pragma once
// The path tracer at equal time (the paper's comparison with Monte Carlo rendering): how
// many samples per pixel the path tracer takes in the neural frame's GPU time on this device, and how noisy
// its image is then, measured against a high-sample render of the same frame traced with other random
// numbers. Time is the host's clock around the work, on both sides: what a user waits for, submissions and
// readbacks included.
#include <nlohmann/json.hpp>
#include <optional>

#include "io/image.h"
#include "render/volume.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Context;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::eval {

struct EqualTimeSettings {
  double budgetMs = 0;     // the neural frame's time (host clock, readback included)
  uint32_t samples = 256;  // of the noise-free stand-in, at least (and at least 16 × the equal-time count)
  int orders = 64;         // scattering orders, as the ground truth
};

// Frame `index` of `scene` (camera and lights on their paths) over the scene's background: renders of 1, 2,
// 4, ... spp (each from the start, in passes of up to 16 samples) until one takes longer than the budget and
// at least 16 spp; the
// count at the budget, interpolated linearly in time, rendered and timed; all against the stand-in. The
// scene's obstacles are path-traced (at the frame's time), as in the truth. `neural`: the neural frame,
// compared with the stand-in too when given.
// Returns {budget_ms, reference_spp, curve: [{spp, ms, image error}], equal_time_spp, equal_time_ms,
// equal_time (image error), neural (image error)}; image errors as metrics::ImageError::json().
nlohmann::json equalTimeStudy(const gpu::Context& context, const gpu::PipelineCache& cache,
                              const scene::Scene& scene, int index, const render::Volume& volume,
                              const EqualTimeSettings& study, const io::Image* neural);

}  // namespace sixway::eval
