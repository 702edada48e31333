// platform.h in standard C++ alone, for systems without POSIX: no process can be looked at and no limit
// read, so those answers are the cautious ones (platform.h).
#include <fstream>
#include <random>
#include <system_error>

#include "platform/platform.h"

namespace sixway::platform {

long processId() {
  static const long id = 1 + long(std::random_device{}() % 999999999u);  // nine digits at most, as a pid
  return id;
}

bool processEnded(long) {
  return false;
}

std::string writeFile(const std::filesystem::path& path, std::span<const uint8_t> bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return "cannot be created";
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  out.close();
  return out ? "" : "the write failed";
}

FileRead readRegularFile(const std::filesystem::path& path, uint64_t maxBytes) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (status.type() == std::filesystem::file_type::not_found) return {};
  if (error) return {{}, "cannot be examined: " + error.message()};
  if (std::filesystem::is_directory(status)) return {{}, "is a directory"};
  if (!std::filesystem::is_regular_file(status))
    return {{}, "is not a regular file (a FIFO, socket or device)"};
  const uint64_t size = std::filesystem::file_size(path, error);
  if (error) return {{}, "cannot be examined: " + error.message()};
  if (size > maxBytes)
    return {
        {},
        "holds " + std::to_string(size >> 20) + " MiB, more than " + std::to_string(maxBytes >> 20) + " MiB"};
  std::ifstream in(path, std::ios::binary);
  FileRead read;
  read.bytes.resize(std::size_t(size));
  in.read(read.bytes.data(), std::streamsize(size));
  read.bytes.resize(std::size_t(in.gcount()));
  return read;
}

std::optional<PathLimits> pathLimits() {
  return std::nullopt;
}

std::optional<uint64_t> addressSpaceLimit() {
  return std::nullopt;
}

uint64_t mappedBytes() {
  return 0;
}

}  // namespace sixway::platform
