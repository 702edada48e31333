#pragma once
// JSON reports (`--report FILE`) and the no-silent-overwrite rule for outputs.
#include <filesystem>
#include <nlohmann/json.hpp>

namespace sixway::io {

// Checks an output file (`--report FILE`) before any work. Throws io::InputError naming `path` when it is
// something other than a regular file (a directory, FIFO, socket or device: never replaced, even with
// `force`); when it exists and `force` is not set; or when the directory that would hold it (its nearest
// existing ancestor) is not a writable directory. Commands call it before the device starts, so an
// unwritable output is one line at once.
void requireWritableFile(const std::filesystem::path& path, bool force);
// The same for an output directory (`--out DIR`): anything there other than a directory is refused, even
// with `force`; an existing directory needs `force` and is written into.
void requireWritableDirectory(const std::filesystem::path& path, bool force);

// Makes the output directory `path` (and its parents). Without `force` the directory itself must not exist:
// it is made with one mkdir that fails if another process made it first, so of two runs started together
// into one new directory only one gets it; the other gets an io::InputError naming the directory. Returns
// whether this call made the directory.
bool claimOutputDirectory(const std::filesystem::path& path, bool force);

// Writes under a temporary name, then renames, so a report is never left half written. Strings that are not
// UTF-8 (paths) are written with U+FFFD in place of their invalid bytes (io::jsonText). The temporary files
// of `path` that killed runs left go first (io::removePartialsOfEndedRuns).
void writeReport(const std::filesystem::path& path, const nlohmann::json& report);

}  // namespace sixway::io
