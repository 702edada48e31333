#pragma once
// Where the volumes of a sequence come from, one frame at a time: the simulation of a scene, or a list of
// OpenVDB files. The flipbook bake (bake_flipbook.h) asks for frames in increasing order.
#include <optional>
#include <string>

#include "render/volume.h"

namespace sixway::render {

class VolumeSequence {
 public:
  virtual ~VolumeSequence() = default;

  // Frames available; frame(i) takes 0 <= i < frameCount().
  virtual int frameCount() const = 0;
  // The volume of frame `index`, or nothing for a frame without smoke (it bakes to a transparent tile).
  // Indices come in increasing order, not necessarily consecutive; the volume's buffers need to stay valid
  // only until the next call.
  virtual std::optional<Volume> frame(int index) = 0;
  // The volume of frame `index` even when it holds no smoke (then all zero); the same order rule.
  virtual Volume volume(int index) = 0;
  // A box that holds every frame's volume: it places the default camera and the billboard.
  virtual Box bounds() const = 0;
  // Says what frame `index` is (a file name, a simulated time), for progress lines and the sidecar.
  virtual std::string frameName(int index) const = 0;
  // The side of the volumes' cells, and the largest density frames [first, first + count) hold (or a bound
  // on it): with the extinction they give the densest cell's optical depth, which sets the bake's light-grid
  // spacing (reference::lightSpacingFor). May read those frames once more.
  virtual float cellSize() const = 0;
  virtual float densityBound(int first, int count) = 0;
};

}  // namespace sixway::render
