#include "io/file_access.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <string>
#include <system_error>

#include "io/error.h"
#include "platform/platform.h"

namespace sixway::io {

namespace fs = std::filesystem;

std::string describeFileType(fs::file_type type) {
  switch (type) {
    case fs::file_type::regular:
      return "a regular file";
    case fs::file_type::directory:
      return "a directory";
    case fs::file_type::symlink:
      return "a symbolic link";
    case fs::file_type::block:
      return "a block device";
    case fs::file_type::character:
      return "a character device";
    case fs::file_type::fifo:
      return "a FIFO";
    case fs::file_type::socket:
      return "a socket";
    default:
      return "a special file";
  }
}

std::string lookupProblem(const fs::path& path, const std::error_code& error) {
  if (error != std::errc::filename_too_long) return error.message();
  const auto tooLong = [](std::string_view what, std::size_t length, long limit) {
    return std::string(what) + " is longer than the system allows (" + std::to_string(length) +
           " characters, at most " + std::to_string(limit) + ")";
  };
  const std::optional<platform::PathLimits> limits = platform::pathLimits();
  if (!limits) return error.message();
  const std::size_t length = path.native().size();
  if (length >= limits->path) return tooLong("path", length, long(limits->path) - 1);
  std::size_t longest = 0;
  for (const fs::path& name : path) longest = std::max(longest, name.native().size());
  if (longest > limits->name) return tooLong("a name in the path", longest, long(limits->name));
  return error.message();
}

std::string regularFileProblem(const fs::path& path, std::string_view missing) {
  std::error_code error;
  const fs::file_type type = fs::status(path, error).type();
  if (type == fs::file_type::not_found) return std::string(missing);
  if (type == fs::file_type::none) return lookupProblem(path, error);
  if (type != fs::file_type::regular) return "is " + describeFileType(type) + ", not a regular file";
  return "";
}

void requireRegularFile(const fs::path& path, std::string_view missing) {
  if (const std::string problem = regularFileProblem(path, missing); !problem.empty())
    throw InputError(path.string(), problem);
}

std::vector<uint8_t> readFileBytes(const fs::path& path) {
  requireRegularFile(path);
  std::ifstream in(path, std::ios::binary);
  std::error_code error;
  const std::uintmax_t size = fs::file_size(path, error);
  if (!in || error) throw InputError(path.string(), "cannot open the file for reading");
  std::vector<uint8_t> bytes(size);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size))) {
    throw InputError(path.string(), "cannot read the file");
  }
  return bytes;
}

void removeNumberedEntries(const fs::path& directory, const std::regex& pattern, fs::file_type type,
                           const std::function<bool(long)>& stale) {
  std::error_code error;
  std::vector<fs::path> doomed;
  for (const auto& entry : fs::directory_iterator(directory, error)) {
    std::smatch match;
    const std::string name = entry.path().filename();
    if (std::regex_match(name, match, pattern) && entry.symlink_status(error).type() == type &&
        stale(std::stol(match[1])))
      doomed.push_back(entry.path());
  }
  for (const fs::path& path : doomed) fs::remove_all(path, error);
}

void removePartialsOfEndedRuns(const fs::path& target) {
  static const std::regex special(R"([.^$|()\[\]{}*+?\\])");
  const std::string name = std::regex_replace(target.filename().string(), special, R"(\$&)");
  const fs::path directory = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  removeNumberedEntries(directory, std::regex("\\." + name + "\\.([0-9]{1,9})\\.partial"),
                        fs::file_type::regular, platform::processEnded);
}

void appendBytes(void* context, void* data, int size) {
  auto& out = *static_cast<std::vector<uint8_t>*>(context);
  const auto* bytes = static_cast<const uint8_t*>(data);
  out.insert(out.end(), bytes, bytes + size);
}

void requireReplaceable(const fs::path& path) {
  std::error_code error;
  const fs::file_type type = fs::symlink_status(path, error).type();
  if (error) return;  // nothing there, or it cannot be looked at: the rename then fails on its own
  if (type == fs::file_type::not_found || type == fs::file_type::regular || type == fs::file_type::symlink)
    return;
  throw InputError(path.string(), "is " + describeFileType(type) + ", not a regular file; not replaced");
}

AtomicFile::AtomicFile(fs::path target) : target_(std::move(target)) {
  const fs::path directory = target_.parent_path().empty() ? fs::path(".") : target_.parent_path();
  std::error_code error;
  if (!fs::is_directory(directory, error)) {
    throw InputError(target_.string(), "cannot write: directory '" + directory.string() + "' does not exist");
  }
  // The process id keeps two processes writing the same target from sharing a temporary file.
  std::string name = ".";
  name += target_.filename().string();
  name += '.';
  name += std::to_string(platform::processId());
  name += ".partial";
  temporary_ = directory / name;
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove(temporary_, ignored);
}

void AtomicFile::writeAll(std::span<const uint8_t> bytes) const {
  if (const std::string problem = platform::writeFile(temporary_, bytes); !problem.empty())
    throw InputError(target_.string(), "cannot write the file: " + problem);
}

void AtomicFile::commit() {
  std::error_code error;
  if (!fs::is_regular_file(temporary_, error)) throw InputError(target_.string(), "cannot write the file");
  requireReplaceable(target_);
  fs::rename(temporary_, target_, error);
  if (error) throw InputError(target_.string(), "cannot write the file: " + error.message());
  committed_ = true;
}

}  // namespace sixway::io
