#pragma once
// What every reader and writer in io does with files: readers check that the input is a readable regular file
// (so "no such file" is one clear line), writers write under a temporary name and rename when complete (so an
// interrupted write never leaves a truncated file under the final name).
#include <cstdint>
#include <filesystem>
#include <vector>

namespace sixway::io {

// Throws InputError naming `path` when it does not exist or is not a regular file.
void requireRegularFile(const std::filesystem::path& path);

// The whole file; throws InputError naming `path` when it cannot be read.
std::vector<uint8_t> readFileBytes(const std::filesystem::path& path);

// A temporary file next to `target`, renamed onto it by commit(); removed if commit() is never reached.
class AtomicFile {
 public:
  // Throws InputError naming `target` when its directory does not exist.
  explicit AtomicFile(std::filesystem::path target);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::filesystem::path& temporaryPath() const { return temporary_; }
  // Throws InputError naming the target when the temporary file is missing or cannot be renamed.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  bool committed_ = false;
};

}  // namespace sixway::io
