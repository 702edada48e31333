#pragma once
// The one-screen summary `sixway eval --scene` prints at the end: per method the final image against the path
// tracer (masked PSNR pooled over the frames, the mean of the frames' PSNRs, the full-frame PSNR) and its
// median GPU and wall time per frame; then the lightmaps, the equal-time path tracer and each method's
// frame-to-frame change over the truth's. From the report's numbers.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sixway::eval {

// `summary`, `equalTime`: the report's "summary" and "equal_time" objects; `methods` in the order shown.
std::string summaryTable(const nlohmann::json& summary, const nlohmann::json& equalTime,
                         const std::vector<std::string>& methods);

}  // namespace sixway::eval
