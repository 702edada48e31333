#include "eval/summary_table.h"

#include <cmath>
#include <cstdio>

namespace sixway::eval {
namespace {

// A number of the report (null where there was nothing to measure) as text of `width` characters.
std::string cell(const nlohmann::json& value, const char* format, int width) {
  char text[32];
  if (value.is_number() && std::isfinite(value.get<double>()))
    std::snprintf(text, sizeof(text), format, width, value.get<double>());
  else
    std::snprintf(text, sizeof(text), "%*s", width, "-");
  return text;
}

const nlohmann::json& at(const nlohmann::json& object, const char* key) {
  static const nlohmann::json null;
  return object.is_object() && object.contains(key) ? object[key] : null;
}

}  // namespace

std::string summaryTable(const nlohmann::json& summary, const nlohmann::json& equalTime,
                         const std::vector<std::string>& methods) {
  std::string table =
      "  method           PSNR masked  mean of frames  full frame  obstacle band  detail   GPU ms/frame  "
      "wall "
      "ms/frame\n";
  for (const std::string& method : methods) {
    const nlohmann::json& image = at(at(summary, "image"), method.c_str());
    const nlohmann::json& times = at(at(summary, "median_ms"), method.c_str());
    char name[32];
    std::snprintf(name, sizeof(name), "  %-15s", method.c_str());
    table += name + cell(at(image, "psnr_masked_db"), "%*.2f", 12) +
             cell(at(image, "mean_frame_psnr_masked_db"), "%*.2f", 16) +
             cell(at(image, "psnr_full_db"), "%*.2f", 12) + cell(at(image, "psnr_band_db"), "%*.2f", 15) +
             cell(at(at(at(summary, "detail"), "methods"), method.c_str()), "%*.2f", 8) +
             cell(at(times, "total_ms"), "%*.1f", 15) + cell(at(times, "wall_ms"), "%*.1f", 15) + "\n";
  }
  table +=
      "  (PSNR in dB against the path tracer, masked to the smoke; the obstacle band within it; detail: "
      "high-pass "
      "energy over the truth's, with --truth-noise; times are medians over the frames)\n";
  table += "  neural lightmaps: " + cell(at(at(summary, "lightmap"), "psnr_masked_db"), "%*.2f", 0) +
           " dB against the single-scattering baker's, " +
           cell(at(at(summary, "lightmap_ms"), "psnr_masked_db"), "%*.2f", 0) +
           " dB against the multiply-scattered ones\n";
  if (equalTime.is_object())
    table += "  path tracer in the neural frame's " + cell(at(equalTime, "budget_ms"), "%*.1f", 0) +
             " ms: " + cell(at(equalTime, "equal_time_spp"), "%*.0f", 0) + " spp, " +
             cell(at(at(equalTime, "equal_time"), "psnr_masked_db"), "%*.2f", 0) + " dB\n";
  const nlohmann::json& temporal = at(summary, "temporal");
  if (temporal.is_object()) {
    const nlohmann::json& truth = at(temporal, "truth");
    table += "  frame-to-frame change (RMS where the smoke is): truth " + cell(at(truth, "rms"), "%*.4f", 0);
    if (at(temporal, "truth_noise_removed") == true)
      table += ", " + cell(at(truth, "rms_without_noise"), "%*.4f", 0) + " without its noise (" +
               cell(at(truth, "noise_rms"), "%*.4f", 0) + ")";
    table += "; x the truth's:";
    for (const std::string& method : methods)
      table +=
          " " + method + " " + cell(at(at(at(temporal, "methods"), method.c_str()), "rms_ratio"), "%*.2f", 0);
    table += "\n";
  }
  return table;
}

}  // namespace sixway::eval
