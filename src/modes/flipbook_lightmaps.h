#pragma once
// traditional and traditional-ms: today's games' flipbook. Its lightmaps are baked from the first frame's
// view only (as a flipbook is) and drawn on a camera-facing billboard whose depth is its plane: the frame has
// no guiding map, its guide and opacity depths are uploaded.
#include <optional>
#include <utility>

#include "modes/baked_lightmaps.h"

namespace sixway::modes {

class FlipbookLightmaps : public BakedLightmaps {
 public:
  FlipbookLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache, const scene::Scene& scene,
                    reference::Scattering scattering, const reference::MultipleScattering& multiple);

  render::ImagePlane update(runtime::RealtimeFrame& frame, const runtime::SourceFrame& current) override;

 private:
  std::optional<std::pair<render::Camera, render::ImagePlane>> bakedView_;  // the first frame's
};

}  // namespace sixway::modes
