#pragma once
// The figures of `sixway eval --scene`'s report (scene_eval.h) made of its measurements: numbers that may not
// be finite, GPU stage times and their medians over the frames, a frame's lightmap PSNRs, and the methods'
// frame-to-frame change next to the truth's.
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "eval/lightmap_metrics.h"
#include "eval/temporal_change.h"
#include "gpu/sequence.h"

namespace sixway::eval {

double median(std::vector<double> values);
// The value, or null when it is not finite (JSON has no NaN).
nlohmann::json number(double v);
// The number, or NaN for null.
double orNan(const nlohmann::json& v);

// Per stage, each stage's time summed over its repeats in the frame (e.g. several bake passes).
nlohmann::json stageTimes(const std::vector<gpu::StageTime>& stages);
// Medians over the frames of each stage and of the total, from the per-frame "stages_ms" of one method.
nlohmann::json medianTimes(const std::vector<nlohmann::json>& frames);

// The lightmap figures of one frame, with the MSEs the PSNRs stand for.
nlohmann::json lightmapFrame(const LightmapMetrics& m);

// Each method's frame-to-frame change next to the truth's (the target: within 20% of it); the truth's with
// its Monte Carlo noise taken out where that was measured (--truth-noise). Null for a single frame.
nlohmann::json temporalSummary(const std::map<std::string, TemporalChange>& methods,
                               const TemporalChange& truth, const std::optional<TemporalChange>& noise);

}  // namespace sixway::eval
