#pragma once
// JSON as text for the files sixway writes. A POSIX path may hold any bytes, and a report or sidecar names
// the paths it was given: bytes that are not UTF-8 are written as U+FFFD (the replacement character), so
// writing never fails on them (nlohmann's default throws type_error 316).
#include <string>

#include <nlohmann/json.hpp>

namespace sixway::io {

// `value` as JSON text; indent < 0: on one line.
std::string jsonText(const nlohmann::json& value, int indent = -1);

}  // namespace sixway::io
