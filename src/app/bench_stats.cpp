#include "app/bench_stats.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace sixway::app {

Timing summarize(std::vector<double> samples) {
  if (samples.empty()) throw std::invalid_argument("summarize: no samples");
  std::sort(samples.begin(), samples.end());
  const size_t n = samples.size();
  const double median = n % 2 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
  return {median, samples.front(), samples.back()};
}

nlohmann::json timingJson(const std::vector<double>& samples) {
  const Timing t = summarize(samples);
  return {{"median_ms", t.median}, {"min_ms", t.min}, {"max_ms", t.max}, {"samples_ms", samples}};
}

void StageTimes::beginRun() {
  ++runs_;
  for (Stage& s : stages_) s.ms.push_back(0.0);
}

StageTimes::Stage& StageTimes::stage(const std::string& name, bool inTotal) {
  if (runs_ == 0) throw std::logic_error("StageTimes: add() before beginRun()");
  for (Stage& s : stages_)
    if (s.name == name) return s;
  if (runs_ > 1) throw std::logic_error("StageTimes: stage \"" + name + "\" is missing from earlier runs");
  stages_.push_back({name, inTotal, {0.0}});
  return stages_.back();
}

void StageTimes::add(const std::string& name, double ms, bool inTotal) {
  stage(name, inTotal).ms.back() += ms;
}

void StageTimes::add(const std::vector<gpu::StageTime>& stages, const std::string& prefix) {
  for (const gpu::StageTime& t : stages) add(prefix + t.name, t.milliseconds);
}

std::vector<double> StageTimes::samples(const std::string& name) const {
  for (const Stage& s : stages_)
    if (s.name == name) return s.ms;
  throw std::invalid_argument("StageTimes: no stage \"" + name + "\"");
}

std::vector<double> StageTimes::totals() const {
  std::vector<double> totals(size_t(runs_), 0.0);
  for (const Stage& s : stages_)
    if (s.inTotal)
      for (size_t r = 0; r < totals.size(); ++r) totals[r] += s.ms[r];
  return totals;
}

nlohmann::json StageTimes::json() const {
  nlohmann::json stages = nlohmann::json::array();
  for (const Stage& s : stages_) {
    nlohmann::json entry = {{"name", s.name}, {"in_total", s.inTotal}};
    entry.update(timingJson(s.ms));
    stages.push_back(entry);
  }
  return {{"runs", runs_}, {"stages", stages}, {"total", timingJson(totals())}};
}

void StageTimes::print(const std::string& title) const {
  std::printf("%s (ms over %d run%s)\n", title.c_str(), runs_, runs_ == 1 ? "" : "s");
  std::printf("  %-30s %10s %10s %10s\n", "stage", "median", "min", "max");
  const auto row = [](const std::string& name, const std::vector<double>& ms) {
    const Timing t = summarize(ms);
    std::printf("  %-30s %10.3f %10.3f %10.3f\n", name.c_str(), t.median, t.min, t.max);
  };
  for (const Stage& s : stages_) row(s.inTotal ? s.name : s.name + " (not in total)", s.ms);
  row("total", totals());
  std::fflush(stdout);
}

}  // namespace sixway::app
