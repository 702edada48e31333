#pragma once
// What fills the six-way lightmaps of a real-time frame (frame_renderer.h): the network
// (network_lightmaps.h), or one of the evaluation's methods (src/modes/). The frame records the
// source's GPU work between the guiding map and the shading, once per volume, and lets it write its values
// before each submission.
#include <vector>

#include "gpu/sequence.h"
#include "render/camera.h"
#include "render/guiding_map.h"
#include "render/volume.h"
#include "runtime/realtime_frame.h"
#include "scene/scene.h"

namespace sixway::runtime {

// This frame as a source sees it before submission.
struct SourceFrame {
  const render::Volume& volume;
  const render::Camera& camera;
  render::ImagePlane billboard;  // the guide's; the volume's bounds in a frame without a guide
  int index;                     // the scene's frame: seeds per-frame noise
};

class LightmapSource {
 public:
  // `stages`: the passes a frame with this source records.
  explicit LightmapSource(FrameStages stages = FrameStages::All) : stages_(stages) {}
  virtual ~LightmapSource() = default;
  LightmapSource(const LightmapSource&) = delete;
  LightmapSource& operator=(const LightmapSource&) = delete;

  FrameStages stages() const { return stages_; }
  // The guiding map's settings: the scene's, unless the source reads the guide its own way.
  virtual render::GuideSettings guide(const scene::Scene& scene) const {
    return render::GuideSettings::fromScene(scene);
  }
  // Records what fills frame.lightmaps() from the guide; nothing for lightmaps uploaded by update().
  virtual void record(gpu::Sequence&, RealtimeFrame&) {}
  // Writes this frame's values into `frame` (uploads); returns the billboard the shading draws.
  virtual render::ImagePlane update(RealtimeFrame&, const SourceFrame& current) { return current.billboard; }
  // GPU time of the last update()'s own work (its recorded work is timed in the frame's sequence).
  virtual std::vector<gpu::StageTime> stageTimes() const { return {}; }

 private:
  FrameStages stages_;
};

}  // namespace sixway::runtime
