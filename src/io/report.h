#pragma once
// JSON reports (`--report FILE`) and the no-silent-overwrite rule for outputs.
#include <filesystem>
#include <nlohmann/json.hpp>

namespace sixway::io {

// Throws io::InputError unless `path` is absent, or present and `force` is set; and unless the directory that
// would hold it (its nearest existing ancestor) is a writable directory. Commands call it before the device
// starts, so an unwritable output is one line at once.
void requireWritable(const std::filesystem::path& path, bool force);
// Writes under a temporary name, then renames, so a report is never left half written.
void writeReport(const std::filesystem::path& path, const nlohmann::json& report);

}  // namespace sixway::io
