#include "app/timings_log.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sixway::app {
namespace {

constexpr double kAbsent = std::numeric_limits<double>::quiet_NaN();

}  // namespace

TimingsLog::TimingsLog(int frames) : capacity_(size_t(std::max(frames, 0))) {
  rows_.reserve(capacity_);
}

size_t TimingsLog::stageIndex(const std::string& name) {
  const auto known = std::find(names_.begin(), names_.end(), name);
  if (known != names_.end()) return size_t(known - names_.begin());
  names_.push_back(name);
  stageMs_.emplace_back();
  stageMs_.back().reserve(capacity_);
  stageMs_.back().resize(rows_.size(), kAbsent);  // the frames before this stage first appeared
  return names_.size() - 1;
}

double TimingsLog::add(int frame, double seconds, const std::vector<gpu::StageTime>& stages,
                       const gpu::MemoryUse& device, uint64_t hostResidentBytes) {
  for (const gpu::StageTime& s : stages) stageIndex(s.name);
  for (std::vector<double>& column : stageMs_) column.push_back(kAbsent);
  double total = 0;
  for (const gpu::StageTime& s : stages) {
    double& ms = stageMs_[stageIndex(s.name)].back();
    ms = (std::isnan(ms) ? 0.0 : ms) + s.milliseconds;
    total += s.milliseconds;
  }
  rows_.push_back({frame, seconds, total, device.bytes, device.allocations, hostResidentBytes});
  return total;
}

nlohmann::json TimingsLog::frames() const {
  nlohmann::json out = nlohmann::json::array();
  for (size_t r = 0; r < rows_.size(); ++r) {
    nlohmann::json stages = nlohmann::json::object();
    for (size_t s = 0; s < names_.size(); ++s)
      if (!std::isnan(stageMs_[s][r])) stages[names_[s]] = stageMs_[s][r];
    const Row& row = rows_[r];
    out.push_back({{"frame", row.frame},
                   {"seconds", row.seconds},
                   {"stages_ms", stages},
                   {"total_ms", row.totalMs},
                   {"device_bytes", row.deviceBytes},
                   {"device_allocations", row.deviceAllocations},
                   {"host_resident_bytes", row.hostResidentBytes}});
  }
  return out;
}

nlohmann::json TimingsLog::medianStageMs() const {
  nlohmann::json out = nlohmann::json::object();
  for (size_t s = 0; s < names_.size(); ++s) {
    std::vector<double> values;
    for (double ms : stageMs_[s])
      if (!std::isnan(ms)) values.push_back(ms);
    if (values.empty()) continue;
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    out[names_[s]] = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
  }
  return out;
}

}  // namespace sixway::app
