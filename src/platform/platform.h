#pragma once
// What sixway needs of the operating system beyond standard C++, in one place: POSIX (posix.cpp), or
// standard C++ alone where POSIX is missing (portable.cpp; what it cannot do is said at each call). The
// runtime's other code includes no system header (repo.runtime_code_is_portable).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sixway::platform {

// This process's id, for temporary names (portable: a random number fixed for the process's life).
long processId();

// Whether process `pid` has ended: it no longer exists, or it is a zombie (it has exited and only its exit
// status waits for a parent that may never collect it). A live process, or one that cannot be looked at, has
// not; portable: never known, so false (nothing another process left is removed).
bool processEnded(long pid);

// Creates or truncates `path` and writes all of `bytes`: "" or the system's words for the failure (a full
// disk, a deferred write error surfacing at close).
std::string writeFile(const std::filesystem::path& path, std::span<const uint8_t> bytes);

// A file read whole if it is a regular file of at most `maxBytes`, opened without waiting for a FIFO's
// writer and never read when it is a FIFO, device, socket or directory: the bytes, or `problem` ("is a
// directory", "is not a regular file (a FIFO, socket or device)", "holds N MiB, more than M MiB", "cannot be
// opened: …"). Nothing there: no bytes and no problem.
struct FileRead {
  std::vector<char> bytes;
  std::string problem;
};
FileRead readRegularFile(const std::filesystem::path& path, uint64_t maxBytes);

// The longest path (bytes, with its terminating zero) and file name the system takes; none where unknown.
struct PathLimits {
  std::size_t path, name;
};
std::optional<PathLimits> pathLimits();

// The address-space limit (ulimit -v) in bytes, none when unlimited or unknown (portable: unknown).
std::optional<uint64_t> addressSpaceLimit();
// The process's mapped address space in bytes; 0 when unknown (portable: unknown).
uint64_t mappedBytes();

}  // namespace sixway::platform
