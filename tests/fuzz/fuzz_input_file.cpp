#include "fuzz_input_file.h"

#include <unistd.h>

#include <fstream>
#include <stdexcept>

namespace sixway::fuzz {

namespace {

struct ScratchDirectory {
  std::filesystem::path path;
  ScratchDirectory()
      : path(std::filesystem::temp_directory_path() / ("sixway_fuzz_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path);
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

}  // namespace

const std::filesystem::path& scratchDirectory() {
  static const ScratchDirectory directory;
  return directory.path;
}

std::filesystem::path writeInput(const std::string& name, const uint8_t* data, std::size_t size) {
  const std::filesystem::path path = scratchDirectory() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  // A fuzz run that silently tests nothing is worse than one that stops.
  if (!out) throw std::runtime_error("cannot write the fuzz input " + path.string());
  return path;
}

}  // namespace sixway::fuzz
