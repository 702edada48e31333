#include "io/report.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <span>
#include <string>

#include "io/error.h"
#include "io/file_access.h"
#include "io/json_text.h"

namespace sixway::io {

namespace fs = std::filesystem;

namespace {

// The directory a new output at `path` would be made in: `path` itself when it is an existing directory
// (written into), else its nearest existing ancestor. Throws unless that is a writable directory.
void requireWritableAncestor(const fs::path& path) {
  std::error_code error;
  const fs::path absolute = fs::absolute(path, error);
  fs::path ancestor = fs::is_directory(absolute, error) ? absolute : absolute.parent_path();
  while (!fs::exists(ancestor, error) && ancestor.has_relative_path()) ancestor = ancestor.parent_path();
  if (!fs::is_directory(ancestor, error))
    throw InputError(path.string(), "cannot write here: '" + ancestor.string() + "' is not a directory");
  if (::access(ancestor.c_str(), W_OK | X_OK) != 0)
    throw InputError(path.string(), "cannot write here: directory '" + ancestor.string() +
                                        "' is not writable (" + std::strerror(errno) + ")");
}

// Throws unless `path` is absent, or present and `force` is set.
void requireAbsentOrForced(const fs::path& path, fs::file_type type, bool force) {
  if (type == fs::file_type::not_found || force) return;
  throw InputError(path.string(), "exists already; pass --force to overwrite it");
}

// The type of the file at `path`, links followed: not_found when absent, when a link leads nowhere, or when
// it cannot be looked at (a directory without search permission: the writable-ancestor check says so). A path
// longer than the system allows throws.
fs::file_type typeAt(const fs::path& path) {
  std::error_code error;
  const fs::file_type type = fs::status(path, error).type();
  if (error == std::errc::filename_too_long) throw InputError(path.string(), lookupProblem(path, error));
  return error ? fs::file_type::not_found : type;
}

}  // namespace

void requireWritableFile(const fs::path& path, bool force) {
  const fs::file_type type = typeAt(path);
  if (type != fs::file_type::not_found && type != fs::file_type::regular)
    throw InputError(path.string(),
                     "is " + describeFileType(type) + ", not a regular file; give a file's path");
  requireAbsentOrForced(path, type, force);
  requireWritableAncestor(path);
}

void requireWritableDirectory(const fs::path& path, bool force) {
  const fs::file_type type = typeAt(path);
  if (type != fs::file_type::not_found && type != fs::file_type::directory)
    throw InputError(path.string(),
                     "is " + describeFileType(type) + ", not a directory; give a directory's path");
  requireAbsentOrForced(path, type, force);
  requireWritableAncestor(path);
}

bool claimOutputDirectory(const fs::path& path, bool force) {
  std::error_code error;
  fs::path absolute = fs::absolute(path, error);
  if (!absolute.has_filename()) absolute = absolute.parent_path();  // "out/" names "out"
  if (!error) fs::create_directories(absolute.parent_path(), error);
  const bool made = !error && fs::create_directory(absolute, error);
  if (error) throw InputError(path.string(), "cannot create the output directory: " + error.message());
  if (!made && !force)
    throw InputError(
        path.string(),
        "exists already: another run made it after this one started; pass --force to write into it");
  if (!made) requireWritableDirectory(path, force);  // something else may have appeared there meanwhile
  return made;
}

void writeReport(const fs::path& path, const nlohmann::json& report) {
  const std::string text = jsonText(report, 2) + '\n';
  removePartialsOfEndedRuns(path);
  AtomicFile file(path);
  file.writeAll(std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
  file.commit();
}

}  // namespace sixway::io
