#include "runtime/frame_renderer.h"

#include <algorithm>

#include "gpu/context.h"
#include "render/billboard.h"
#include "render/scene_frame.h"

namespace sixway::runtime {

FrameView sceneView(const scene::Scene& scene, int index) {
  return {render::sceneCamera(scene.camera, index), render::sceneLights(scene.lights, index)};
}

FrameRenderer::FrameRenderer(const gpu::Context& context, const gpu::PipelineCache& cache,
                             const scene::Scene& scene, FrameTarget target, uint32_t shadowTiles,
                             std::unique_ptr<LightmapSource> source)
    : source_(std::move(source)),
      frame_(context, cache, scene, std::move(target), shadowTiles, source_->guide(scene)),
      sequence_(context),
      context_(&context) {}

void FrameRenderer::replaceObstacles(const std::vector<scene::Obstacle>& obstacles,
                                     std::optional<uint64_t> frame) {
  // Whatever may throw comes first: nothing that frames in flight run is let go on the way.
  auto meshes = std::make_unique<render::ObstacleMeshes>(*context_, obstacles, gpu::MemoryKind::HostUpload);
  retired_.reserve(retired_.size() + 1);
  Retired old{frame.value_or(0) + context_->framesInFlight(), sequence_.release(), std::move(composites_),
              frame_.replaceObstacles(std::move(meshes))};
  composites_.clear();
  if (frame) retired_.push_back(std::move(old));
}

gpu::Sequence& FrameRenderer::prepare(const FrameInput& input) {
  if (input.frame)
    std::erase_if(retired_, [&](const Retired& r) { return r.until <= *input.frame; });
  else
    retired_.clear();
  const render::Volume& volume = input.volume;
  const FrameStages stages = source_->stages();
  // Recording allocates what the passes need for this volume, so it comes before their per-frame values.
  gpu::Sequence& sequence =
      sequence_.get({render::handleKey(volume.density->handle()), input.generation}, [&](gpu::Sequence& s) {
        frame_.record(s, volume, stages, [&](gpu::Sequence& s) { source_->record(s, frame_); });
      });
  const render::Camera& camera = input.view.camera;
  frame_.updateScene(camera, input.view.lights, input.seconds, input.plane, input.targetDepth);
  notes_ = frame_.takeNotes();
  const render::Box volumeBox = volume.grid.bounds();
  const bool guided = stages == FrameStages::All || stages == FrameStages::UpToGuide;
  const render::ImagePlane billboard = guided ? frame_.updateGuide(camera, volumeBox, input.index)
                                              : render::billboardBounds(camera, volumeBox, 1.0f);
  frame_.updateShading(camera, input.view.lights,
                       source_->update(frame_, {volume, camera, billboard, input.index}), volumeBox);
  return sequence;
}

void FrameRenderer::forgetComposites() {
  composites_.clear();
}

gpu::Sequence& FrameRenderer::composite() {
  // At least one more than the frames in flight: the least recently used one then last ran framesInFlight
  // or more frames ago and has completed, so it can go; four covers a ring of three targets.
  const size_t kept = std::max<size_t>(4, context_->framesInFlight() + 1);
  if (compositesOf_ != sequence_.recordings()) {  // the passes it reads may have been made anew
    composites_.clear();
    compositesOf_ = sequence_.recordings();
  }
  const std::vector<uint64_t> key = frame_.engineTargetKey();
  auto found =
      std::find_if(composites_.begin(), composites_.end(), [&](const Composite& c) { return c.key == key; });
  if (found == composites_.end()) {
    auto fresh = std::make_unique<gpu::Sequence>(*context_);
    frame_.recordComposite(*fresh);
    fresh->finish();
    if (composites_.size() >= kept) composites_.pop_back();
    composites_.insert(composites_.begin(), Composite{key, std::move(fresh)});
  } else {
    std::rotate(composites_.begin(), found, found + 1);
  }
  return *composites_.front().sequence;
}

}  // namespace sixway::runtime
