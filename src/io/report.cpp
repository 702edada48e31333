#include "io/report.h"

#include <fstream>

#include "io/error.h"
#include "io/file_access.h"

namespace sixway::io {

void requireWritable(const std::filesystem::path& path, bool force) {
  if (std::filesystem::exists(path) && !force)
    throw io::InputError(path.string(), "exists already; pass --force to overwrite it");
}

void writeReport(const std::filesystem::path& path, const nlohmann::json& report) {
  io::AtomicFile file(path);
  {
    std::ofstream out(file.temporaryPath());
    try {
      out << report.dump(2) << '\n';
    } catch (const nlohmann::json::type_error& e) {  // a string that is not UTF-8
      throw io::InputError(path.string(), std::string("cannot write the report: ") + e.what());
    }
    if (!out.flush()) throw io::InputError(path.string(), "cannot be written");
  }
  file.commit();
}

}  // namespace sixway::io
