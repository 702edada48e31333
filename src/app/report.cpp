#include "app/report.h"

#include <unistd.h>
#include <fstream>

#include "io/error.h"

namespace sixway::app {

void requireWritable(const std::filesystem::path& path, bool force) {
  if (std::filesystem::exists(path) && !force)
    throw io::InputError(path.string(), "exists already; pass --force to overwrite it");
}

void writeReport(const std::filesystem::path& path, const nlohmann::json& report) {
  std::filesystem::path temporary = path;
  temporary += ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(temporary);
    out << report.dump(2) << '\n';
    if (!out) throw io::InputError(path.string(), "cannot be written");
  }
  std::filesystem::rename(temporary, path);
}

}  // namespace sixway::app
