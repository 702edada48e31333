#include "io/report.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <span>
#include <string>

#include "io/error.h"
#include "io/file_access.h"

namespace sixway::io {

void requireWritable(const std::filesystem::path& path, bool force) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::exists(path, error) && !force)
    throw io::InputError(path.string(), "exists already; pass --force to overwrite it");
  // An existing output directory (render --out with --force) is written into; anything else is made in the
  // nearest directory that exists.
  const fs::path absolute = fs::absolute(path, error);
  fs::path ancestor = fs::is_directory(absolute, error) ? absolute : absolute.parent_path();
  while (!fs::exists(ancestor, error) && ancestor.has_relative_path()) ancestor = ancestor.parent_path();
  if (!fs::is_directory(ancestor, error))
    throw io::InputError(path.string(), "cannot write here: '" + ancestor.string() + "' is not a directory");
  if (::access(ancestor.c_str(), W_OK | X_OK) != 0)
    throw io::InputError(path.string(), "cannot write here: directory '" + ancestor.string() +
                                            "' is not writable (" + std::strerror(errno) + ")");
}

void writeReport(const std::filesystem::path& path, const nlohmann::json& report) {
  std::string text;
  try {
    text = report.dump(2) + '\n';
  } catch (const nlohmann::json::type_error& e) {  // a string that is not UTF-8
    throw io::InputError(path.string(), std::string("cannot write the report: ") + e.what());
  }
  io::AtomicFile file(path);
  file.writeAll(std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
  file.commit();
}

}  // namespace sixway::io
