#include "eval/scene_eval_figures.h"

#include <algorithm>
#include <cmath>

namespace sixway::eval {
namespace {

double totalMs(const nlohmann::json& stages) {
  double total = 0;
  for (const auto& [name, ms] : stages.items()) total += ms.get<double>();
  return total;
}

}  // namespace

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

nlohmann::json number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

double orNan(const nlohmann::json& v) {
  return v.is_number() ? v.get<double>() : NAN;
}

nlohmann::json stageTimes(const std::vector<gpu::StageTime>& stages) {
  nlohmann::json json = nlohmann::json::object();
  for (const gpu::StageTime& s : stages) json[s.name] = json.value(s.name, 0.0) + s.milliseconds;
  return json;
}

nlohmann::json medianTimes(const std::vector<nlohmann::json>& frames) {
  std::map<std::string, std::vector<double>> perStage;
  std::vector<double> totals;
  for (const nlohmann::json& f : frames) {
    for (const auto& [name, ms] : f.items()) perStage[name].push_back(ms.get<double>());
    totals.push_back(totalMs(f));
  }
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& [name, values] : perStage) stages[name] = median(values);
  return {{"stages_ms", stages}, {"total_ms", median(totals)}};
}

nlohmann::json lightmapFrame(const LightmapMetrics& m) {
  const nlohmann::json s = m.summary();
  nlohmann::json out = {{"psnr_masked_db", s["psnr_masked_db"]}, {"psnr_full_db", s["psnr_full_db"]}};
  out["mse_masked"] = number(std::pow(10.0, -orNan(s["psnr_masked_db"]) / 10.0));
  out["mse_full"] = number(std::pow(10.0, -orNan(s["psnr_full_db"]) / 10.0));
  return out;
}

nlohmann::json temporalSummary(const std::map<std::string, TemporalChange>& methods,
                               const TemporalChange& truth, const std::optional<TemporalChange>& noise) {
  if (truth.values == 0) return nullptr;
  nlohmann::json truthJson = temporalJson(truth);
  const double truthRms = noise ? rmsWithoutNoise(truth, *noise) : truth.rms();
  truthJson["noise_rms"] = noise ? number(noise->rms()) : nlohmann::json(nullptr);
  truthJson["rms_without_noise"] = noise ? number(truthRms) : nlohmann::json(nullptr);
  nlohmann::json json = {{"truth", truthJson}, {"truth_noise_removed", noise.has_value()}};
  for (const auto& [method, change] : methods) {
    nlohmann::json m = temporalJson(change);
    m["rms_ratio"] = number(truthRms > 0 ? change.rms() / truthRms : NAN);
    json["methods"][method] = m;
  }
  return json;
}

}  // namespace sixway::eval
