#include "app/render_frame_loop.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "app/process_memory.h"
#include "app/stop_on_signal.h"
#include "metrics/image_metrics.h"
#include "runtime/scene_volumes.h"

namespace sixway::app {

RenderFrameLoop::RenderFrameLoop(sixway::Device& device, const scene::Scene& scene, RenderFrameSource& source,
                                 FrameWriter& writer, int frames)
    : device_(device), scene_(scene), source_(source), writer_(writer), frames_(frames), timings_(frames) {
  coverage_.reserve(size_t(frames));
}

void RenderFrameLoop::run(int warmup) {
  started_ = std::chrono::steady_clock::now();
  for (int i = 0; i < frames_; ++i) renderFrame(i, warmup);
}

void RenderFrameLoop::renderFrame(int i, int warmup) {
  throwIfStopped();
  const modes::RenderedFrame frame = source_.render(warmup + i);
  writer_.write(i, frame.image);
  if (frame.image.channelCount() == 4) checkPixels(i, frame.image);
  for (const std::string& note : frame.notes) std::fprintf(stderr, "sixway: note: %s\n", note.c_str());

  // Memory in use, for long-run checks: flat from the first frames on, or something leaks.
  const sixway::Device::MemoryUse memory = device_.memoryUse();
  const double total = timings_.add(i, runtime::SimulatedVolumes::frameSeconds(scene_, warmup + i),
                                    frame.stages, {memory.allocations, memory.bytes}, residentSetBytes());
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  std::printf("  frame %d/%d: %.1f ms GPU, %.1f s elapsed, ETA %.0f s\n", i + 1, frames_, total, elapsed,
              elapsed / (i + 1) * (frames_ - i - 1));
  std::fflush(stdout);
}

void RenderFrameLoop::checkPixels(int i, const io::Image& image) {
  coverage_.push_back(metrics::alphaCoverage(image));
  const metrics::ImageFaults f = metrics::imageFaults(image);
  faults_.push_back({{"not_finite", f.notFinite},
                     {"negative", f.negative},
                     {"dark_dots", f.darkDots},
                     {"first_pixels", f.first}});
  faultTotal_ += f.total();
  if (f.total() > 0) std::fprintf(stderr, "sixway: frame %d has %s\n", i, metrics::describeFaults(f).c_str());
}

std::vector<double>::const_iterator RenderFrameLoop::lastFrames() const {
  return coverage_.end() - std::min<ptrdiff_t>(16, ptrdiff_t(coverage_.size()));
}

double RenderFrameLoop::leastCoverage() const {
  return coverage_.empty() ? 0.0 : *std::min_element(lastFrames(), coverage_.end());
}

void RenderFrameLoop::addChecks(nlohmann::json& report) const {
  if (coverage_.empty()) return;
  report["coverage"] = {
      {"alpha_threshold", 0.1}, {"per_frame", coverage_}, {"least_of_last_16", leastCoverage()}};
  report["pixel_faults"] = {{"total", faultTotal_}, {"per_frame", faults_}};
}

void RenderFrameLoop::printCoverage() const {
  if (coverage_.empty()) return;
  std::printf("sixway render: the smoke covers %.1f%% of the picture at least, over the last %td frames\n",
              100.0 * leastCoverage(), coverage_.end() - lastFrames());
}

}  // namespace sixway::app
