// platform.h on POSIX systems (Linux: /proc for zombies and the mapped size).
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstring>
#include <fstream>

#include "platform/platform.h"

namespace sixway::platform {

long processId() {
  return long(::getpid());
}

bool processEnded(long pid) {
  if (pid <= 0) return false;
  if (::kill(pid_t(pid), 0) != 0) return errno == ESRCH;
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  std::getline(stat, line);
  const size_t command = line.rfind(')');  // the state follows the command name, which may hold spaces
  return command != std::string::npos && line.compare(command, 3, ") Z") == 0;
}

std::string writeFile(const std::filesystem::path& path, std::span<const uint8_t> bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return std::strerror(errno);
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : ENOSPC;  // a write of 0 bytes makes no progress: the disk is full
      ::close(fd);
      return std::strerror(error);
    }
    written += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) return std::strerror(errno);  // a deferred write error (NFS, quotas) surfaces here
  return "";
}

FileRead readRegularFile(const std::filesystem::path& path, uint64_t maxBytes) {
  // O_NONBLOCK: opening a FIFO does not wait for a writer; fstat then tells what was opened.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return {{}, errno == ENOENT ? "" : std::string("cannot be opened: ") + std::strerror(errno)};
  FileRead read;
  struct stat info {};
  if (::fstat(fd, &info) != 0)
    read.problem = std::string("cannot be examined: ") + std::strerror(errno);
  else if (!S_ISREG(info.st_mode))
    read.problem =
        S_ISDIR(info.st_mode) ? "is a directory" : "is not a regular file (a FIFO, socket or device)";
  else if (uint64_t(info.st_size) > maxBytes)
    read.problem = "holds " + std::to_string(info.st_size >> 20) + " MiB, more than " +
                   std::to_string(maxBytes >> 20) + " MiB";
  if (read.problem.empty()) {  // fewer bytes when the file shrank meanwhile
    read.bytes.resize(std::size_t(info.st_size));
    std::size_t done = 0;
    while (done < read.bytes.size()) {
      const ssize_t got = ::read(fd, read.bytes.data() + done, read.bytes.size() - done);
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) break;
      done += std::size_t(got);
    }
    read.bytes.resize(done);
  }
  ::close(fd);
  return read;
}

std::optional<PathLimits> pathLimits() {
  return PathLimits{PATH_MAX, NAME_MAX};
}

std::optional<uint64_t> addressSpaceLimit() {
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return std::nullopt;
  return uint64_t(limit.rlim_cur);
}

uint64_t mappedBytes() {
  std::ifstream statm("/proc/self/statm");  // the first field: the mapped size in pages
  uint64_t pages = 0;
  if (!(statm >> pages)) return 0;
  return pages * uint64_t(::sysconf(_SC_PAGESIZE));
}

}  // namespace sixway::platform
