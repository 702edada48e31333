#pragma once
// The frames of `sixway render` (render_command.h) after the warm-up, each rendered, written, its pixels
// checked (coverage and faults, in the modes with alpha), its notes printed, its GPU times and the memory in
// use logged, and a line on the terminal.
#include <sixway/device.h>
#include <chrono>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "app/frame_writer.h"
#include "app/render_frame_source.h"
#include "app/timings_log.h"
#include "scene/scene.h"

namespace sixway::app {

class RenderFrameLoop {
 public:
  RenderFrameLoop(sixway::Device& device, const scene::Scene& scene, RenderFrameSource& source,
                  FrameWriter& writer, int frames);

  // Frames warmup … warmup + frames - 1 of the scene, written as 0 … frames - 1.
  void run(int warmup);
  const TimingsLog& timings() const { return timings_; }
  // Adds the coverage and the pixel faults to the report, in the modes with alpha.
  void addChecks(nlohmann::json& report) const;
  // The line saying how much of the picture the smoke covers at least, in the modes with alpha.
  void printCoverage() const;

 private:
  void renderFrame(int i, int warmup);
  void checkPixels(int i, const io::Image& image);
  // The last 16 frames' least coverage: a run that ends on a developed plume fills the picture there.
  double leastCoverage() const;
  std::vector<double>::const_iterator lastFrames() const;

  sixway::Device& device_;
  const scene::Scene& scene_;
  RenderFrameSource& source_;
  FrameWriter& writer_;
  const int frames_;
  TimingsLog timings_;
  std::chrono::steady_clock::time_point started_;
  // Per frame: the fraction of pixels the smoke covers (alpha ≥ 0.1); none in the modes without alpha
  // (guide).
  std::vector<double> coverage_;
  // Per frame: pixels no renderer should make (metrics::imageFaults), in the modes with alpha.
  nlohmann::json faults_ = nlohmann::json::array();
  uint64_t faultTotal_ = 0;
};

}  // namespace sixway::app
