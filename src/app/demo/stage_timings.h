#pragma once
// The demo's per-stage GPU time graph: each frame's stage times (the simulation's and the frame's
// timestamps) summed into the stages of docs/conventions.md, "The frame", with a history for the plots.
#include <array>
#include <deque>
#include <string>
#include <vector>

#include "gpu/sequence.h"

namespace sixway::app::demo {

enum class Stage { Simulation, Advection, GuidingMap, Network, Baker, Shadows, Obstacles, Shading, Count };
const char* stageName(Stage stage);

struct FrameStages {
  std::array<float, size_t(Stage::Count)> milliseconds{};
  float total() const;
};

// Sorts a frame's stages: the simulation's ("sim/lbm", "sim/obstacles", "sim/forces+watchdog" →
// simulation; "sim/smoke" → advection) and the renderer's ("guide", "network", "bake/…", "shadow maps",
// "obstacles", "shade", "guide lightmaps").
FrameStages sortStages(const std::vector<gpu::StageTime>& frame);

class StageHistory {
 public:
  explicit StageHistory(size_t length = 240) : length_(length) {}
  void add(const FrameStages& frame, float wallSeconds);
  // Oldest first, for ImGui::PlotLines.
  std::vector<float> series(Stage stage) const;
  std::vector<float> totals() const;
  const FrameStages& last() const { return frames_.back().stages; }
  bool empty() const { return frames_.empty(); }
  int size() const { return int(frames_.size()); }
  // Frames per second over the wall-clock times of the history.
  float framesPerSecond() const;
  // The mean of each stage over the history.
  FrameStages mean() const;

 private:
  struct Entry {
    FrameStages stages;
    float wallSeconds;
  };
  size_t length_;
  std::deque<Entry> frames_;
};

}  // namespace sixway::app::demo
