#pragma once
// The real-time frame of docs/real-time-rendering.md, the one frame every tool renders: RealtimeFrame's
// passes with a lightmap source (lightmap_source.h), recorded once per volume into one sequence and replayed,
// and this frame's values written before each submission. SmokeRenderer runs it with the network; the modes
// of `sixway render` (src/modes/) with theirs.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gpu/sequence.h"
#include "render/camera.h"
#include "render/projection.h"
#include "render/recorded_sequence.h"
#include "render/volume.h"
#include "runtime/lightmap_source.h"
#include "runtime/realtime_frame.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Context;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::runtime {

// Where a frame is seen from and what lights it.
struct FrameView {
  render::Camera camera;
  std::vector<scene::Light> lights;
};
// The scene's camera and lights on their paths at frame `index`.
FrameView sceneView(const scene::Scene& scene, int index);

struct FrameInput {
  render::Volume volume;
  uint64_t generation = 0;  // tells apart volumes that may share a buffer handle (a restarted simulation's)
  FrameView view;
  int index = 0;         // the scene's frame: the guide's jitter, the sources' noise
  double seconds = 0.0;  // the obstacles' time
  // An engine's projection (RealtimeFrame::updateScene): the image-plane rectangle its target covers (unset:
  // the camera's full frame) and what its depth buffer holds (unset on sixway's own target).
  std::optional<render::ImagePlane> plane;
  std::optional<render::DepthMapping> targetDepth;
  // The engine's frame number being recorded (EngineDevice::framesInFlight's promise frees what earlier
  // frames ran); unset on sixway's own device, which waits for each frame.
  std::optional<uint64_t> frame;
};

class FrameRenderer {
 public:
  // `scene` outlives the renderer; the guiding map takes the source's settings.
  FrameRenderer(const gpu::Context& context, const gpu::PipelineCache& cache, const scene::Scene& scene,
                FrameTarget target, uint32_t shadowTiles, std::unique_ptr<LightmapSource> source);

  // Records the passes when the volume differs from the last frame's, writes this frame's values, and returns
  // the sequence to submit or record: the whole frame, or with an engine target all but the composite.
  gpu::Sequence& prepare(const FrameInput& input);
  // With an engine target, after prepare(): the shading into the frame's target (RealtimeFrame::
  // setEngineTarget), recorded once per target while the prepared sequence stays; the last few targets'
  // recordings are kept (framesInFlight + 1, at least four), so an engine that cycles through its frames'
  // images records each once.
  gpu::Sequence& composite();
  // Drops the kept composites (their targets are gone; the GPU is done with them).
  void forgetComposites();
  // Another set of obstacles to draw and shadow from the next prepare() on, its meshes in host-visible
  // memory (made without a submission), which records the passes again. What the frames in flight may still
  // run is kept until frame `frame` + framesInFlight is prepared (unset: on sixway's own device, dropped
  // now).
  void replaceObstacles(const std::vector<scene::Obstacle>& obstacles, std::optional<uint64_t> frame);

  // What the last prepare() could not do as asked, for the user (RealtimeFrame::takeNotes).
  const std::vector<std::string>& notes() const { return notes_; }
  RealtimeFrame& frame() { return frame_; }
  const RealtimeFrame& frame() const { return frame_; }
  LightmapSource& source() { return *source_; }
  const LightmapSource& source() const { return *source_; }

 private:
  std::unique_ptr<LightmapSource> source_;  // before the frame, whose guide it sets
  RealtimeFrame frame_;
  render::RecordedSequence sequence_;
  struct Composite {
    std::vector<uint64_t> key;
    std::unique_ptr<gpu::Sequence> sequence;
  };
  std::vector<Composite> composites_;  // most recently used first
  uint64_t compositesOf_ = 0;          // the prepared sequence's recording they were made with
  // Replaced by replaceObstacles while frames in flight may run them: until the frame number.
  struct Retired {
    uint64_t until;
    std::unique_ptr<gpu::Sequence> sequence;
    std::vector<Composite> composites;
    std::unique_ptr<render::ObstacleMeshes> meshes;
  };
  std::vector<Retired> retired_;
  const gpu::Context* context_;
  std::vector<std::string> notes_;
};

}  // namespace sixway::runtime
