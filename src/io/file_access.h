#pragma once
// What every reader and writer in io does with files: readers check that the input is a readable regular file
// (so "no such file" is one clear line), writers write under a temporary name and rename when complete (so an
// interrupted write never leaves a truncated file under the final name).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <regex>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace sixway::io {

// "a directory", "a FIFO", "a socket", "a character device", …: what a file of type `type` is, for messages.
std::string describeFileType(std::filesystem::file_type type);

// Throws InputError naming `path` and what it is when something other than a regular file or a symbolic link
// is there (a directory, FIFO, socket or device): an output is renamed onto its name only when that replaces
// a file, never a special file. Nothing there is fine.
void requireReplaceable(const std::filesystem::path& path);

// Why `path` cannot be looked at when fs::status failed with `error` for a reason other than its absence:
// "path is longer than the system allows (5000 characters, at most 4095)" (std::filesystem::exists says
// false then, as if the file were missing), or the system's words ("Permission denied").
std::string lookupProblem(const std::filesystem::path& path, const std::error_code& error);

// "" when `path` is a regular file (links followed); else why not, for "<path>: <problem>": `missing` when
// nothing is there, "is a FIFO, not a regular file" (a directory, device or socket likewise), or
// lookupProblem. Never opens the file, so a FIFO or a device is not read.
std::string regularFileProblem(const std::filesystem::path& path, std::string_view missing = "no such file");

// Throws InputError naming `path` and regularFileProblem unless it is a regular file.
void requireRegularFile(const std::filesystem::path& path, std::string_view missing = "no such file");

// The whole file; throws InputError naming `path` when it cannot be read.
std::vector<uint8_t> readFileBytes(const std::filesystem::path& path);

// Clean-up of numbered outputs: removes (recursively) each entry of `directory` of the given type whose name
// matches `pattern`, a regex whose first group is 1 to 9 digits, and whose number `stale` accepts. Errors are
// ignored.
void removeNumberedEntries(const std::filesystem::path& directory, const std::regex& pattern,
                           std::filesystem::file_type type, const std::function<bool(long)>& stale);

// Removes the temporary files of `target` (AtomicFile's `.<name>.<pid>.partial`, from C++ or Python) whose
// process has ended: a run killed between its write and the rename leaves one, and the next run that writes
// `target` calls this. Never a live process's. It reads the whole directory, so writers of many files into
// one directory (frames in a staging directory, which goes whole) do not call it.
void removePartialsOfEndedRuns(const std::filesystem::path& target);

// stb_image_write's write callback (stbi_write_*_to_func): appends to the std::vector<uint8_t> `context`.
void appendBytes(void* context, void* data, int size);

// A temporary file next to `target` (`.<name>.<pid>.partial`), renamed onto it by commit(); removed if
// commit() is never reached. A process killed between its write and the rename leaves it behind: see
// removePartialsOfEndedRuns.
class AtomicFile {
 public:
  // Throws InputError naming `target` when its directory does not exist.
  explicit AtomicFile(std::filesystem::path target);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::filesystem::path& temporaryPath() const { return temporary_; }
  // Writes `bytes` as the temporary file's whole content, checking every write and the close: a full disk
  // (ENOSPC) or a short write throws InputError naming the target and the system's reason. For writers that
  // can encode into memory (PNG, TGA, VDB), whose libraries do not report failed writes themselves.
  void writeAll(std::span<const uint8_t> bytes) const;
  // Throws InputError naming the target when the temporary file is missing or cannot be renamed, or when the
  // target is a directory or special file (requireReplaceable).
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  bool committed_ = false;
};

}  // namespace sixway::io
