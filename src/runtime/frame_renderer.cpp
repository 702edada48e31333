#include "runtime/frame_renderer.h"

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
      sequence_(context) {}

gpu::Sequence& FrameRenderer::prepare(const FrameInput& input) {
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

}  // namespace sixway::runtime
