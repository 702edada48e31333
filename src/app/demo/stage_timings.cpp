#include "app/demo/stage_timings.h"

#include <algorithm>
#include <numeric>

namespace sixway::app::demo {

const char* stageName(Stage stage) {
  static const std::array<const char*, size_t(Stage::Count)> names = {
      "simulation", "advection", "guiding map", "network", "baker", "shadows", "obstacles", "shading"};
  return names[size_t(stage)];
}

float FrameStages::total() const {
  return std::accumulate(milliseconds.begin(), milliseconds.end(), 0.0f);
}

FrameStages sortStages(const std::vector<gpu::StageTime>& frame) {
  FrameStages s;
  auto& ms = s.milliseconds;
  for (const gpu::StageTime& t : frame) {
    Stage stage = Stage::Shading;
    if (t.name == "sim/smoke")
      stage = Stage::Advection;
    else if (t.name.rfind("sim/", 0) == 0)
      stage = Stage::Simulation;
    else if (t.name == "guide")
      stage = Stage::GuidingMap;
    else if (t.name == "network" || t.name == "guide lightmaps")
      stage = Stage::Network;
    else if (t.name.rfind("bake/", 0) == 0 || t.name == "path trace")
      stage = Stage::Baker;
    else if (t.name == "shadow maps")
      stage = Stage::Shadows;
    else if (t.name == "obstacles")
      stage = Stage::Obstacles;
    ms[size_t(stage)] += float(t.milliseconds);
  }
  return s;
}

void StageHistory::add(const FrameStages& frame, float wallSeconds) {
  frames_.push_back({frame, wallSeconds});
  while (frames_.size() > length_) frames_.pop_front();
}

std::vector<float> StageHistory::series(Stage stage) const {
  std::vector<float> values;
  for (const Entry& e : frames_) values.push_back(e.stages.milliseconds[size_t(stage)]);
  return values;
}

std::vector<float> StageHistory::totals() const {
  std::vector<float> values;
  for (const Entry& e : frames_) values.push_back(e.stages.total());
  return values;
}

FrameStages StageHistory::mean() const {
  FrameStages m;
  for (const Entry& e : frames_)
    for (size_t s = 0; s < m.milliseconds.size(); ++s) m.milliseconds[s] += e.stages.milliseconds[s];
  for (float& v : m.milliseconds) v /= float(std::max<size_t>(frames_.size(), 1));
  return m;
}

float StageHistory::framesPerSecond() const {
  float seconds = 0;
  for (const Entry& e : frames_) seconds += e.wallSeconds;
  return seconds > 0 ? float(frames_.size()) / seconds : 0.0f;
}

}  // namespace sixway::app::demo
