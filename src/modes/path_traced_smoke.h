#pragma once
// pathtrace: the volumetric path tracer's smoke and obstacles (the truth; reference::PathTracer, stage "path
// trace") composited on the host over the frame's rasterized background.
#include <memory>
#include <optional>
#include <vector>

#include "gpu/sequence.h"
#include "io/image.h"
#include "modes/render_mode.h"
#include "reference/path_tracer.h"
#include "render/obstacle_bvh.h"
#include "runtime/frame_renderer.h"
#include "scene/scene.h"

namespace sixway::modes {

class PathTracedSmoke {
 public:
  // `scene` and `options` outlive it (its ModeRenderer's).
  PathTracedSmoke(const gpu::Context& context, const gpu::PipelineCache& cache, const scene::Scene& scene,
                  const ModeOptions& options);

  // Moves obstacle `obstacle` along `motion` from now on.
  void setObstacleMotion(size_t obstacle, std::optional<scene::Motion> motion);
  // Traces frame `index` of `volume` from `view`, obstacles at `seconds`, over `frame` (RGBA, premultiplied);
  // adds its GPU time to `stages`.
  void composite(io::Image& frame, const runtime::FrameView& view, int index, double seconds,
                 const render::Volume& volume, std::vector<gpu::StageTime>& stages);

 private:
  const scene::Scene& scene_;
  const ModeOptions& options_;
  reference::PathTracer tracer_;
  std::unique_ptr<render::ObstacleBvh> obstacles_;  // none without obstacles
};

}  // namespace sixway::modes
