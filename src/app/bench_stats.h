#pragma once
// Repeated GPU timings of named stages, summarized the way docs/conventions.md, "Metrics" asks: the median of
// repeated runs after warm-up, with the min and max next to it.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gpu/sequence.h"

namespace sixway::app {

struct Timing {
  double median = 0, min = 0, max = 0;
};
// Throws std::invalid_argument for no samples.
Timing summarize(std::vector<double> samples);
// {"median_ms", "min_ms", "max_ms", "samples_ms": [...]}.
nlohmann::json timingJson(const std::vector<double>& samples);

// Stages × runs: each run adds its stages (a name given twice in one run adds up, e.g. the passes of a
// frame's lattice steps); stages keep the order of their first appearance.
class StageTimes {
 public:
  void beginRun();
  // `inTotal` false: reported, but not part of the run's total (e.g. an alternative to a stage of the total).
  void add(const std::string& stage, double ms, bool inTotal = true);
  void add(const std::vector<gpu::StageTime>& stages, const std::string& prefix = "");

  int runs() const { return runs_; }
  std::vector<double> samples(const std::string& stage) const;
  std::vector<double> totals() const;
  // {"runs", "stages": [{"name", "in_total", median_ms, ...}], "total": {median_ms, ...}}.
  nlohmann::json json() const;
  // One row per stage and the total: median, min, max in ms.
  void print(const std::string& title) const;

 private:
  struct Stage {
    std::string name;
    bool inTotal;
    std::vector<double> ms;  // one per run
  };
  Stage& stage(const std::string& name, bool inTotal);
  std::vector<Stage> stages_;
  int runs_ = 0;
};

}  // namespace sixway::app
