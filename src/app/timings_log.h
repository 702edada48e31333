#pragma once
// The per-frame rows of `sixway render`'s timings.json: GPU time per stage, the frame's time in the scene,
// and the memory in use (our device buffers and images, the process's resident set). Kept as numbers in
// columns reserved for every frame up front, and turned into JSON only at the end, so that a run of 10,000
// frames holds no growing JSON tree and its memory stays flat (the long-run test, docs/robustness.md).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "gpu/sequence.h"

namespace sixway::app {

class TimingsLog {
 public:
  explicit TimingsLog(int frames);

  // One frame: its stages (times of the same name are added up). Returns the frame's total GPU time, ms.
  double add(int frame, double seconds, const std::vector<gpu::StageTime>& stages,
             const gpu::MemoryUse& device, uint64_t hostResidentBytes);

  // [{frame, seconds, stages_ms: {name: ms}, total_ms, device_bytes, device_allocations,
  // host_resident_bytes}]
  nlohmann::json frames() const;
  // {name: median ms over the frames that had the stage}
  nlohmann::json medianStageMs() const;

 private:
  struct Row {
    int frame;
    double seconds, totalMs;
    uint64_t deviceBytes, deviceAllocations, hostResidentBytes;
  };
  size_t stageIndex(const std::string& name);

  size_t capacity_;
  std::vector<std::string> names_;            // stage names, in the order first seen
  std::vector<std::vector<double>> stageMs_;  // [stage][row]; NaN where that frame had no such stage
  std::vector<Row> rows_;
};

}  // namespace sixway::app
