#include "gpu/address_space.h"

#include <sys/resource.h>
#include <unistd.h>

#include <fstream>

#include "gpu/check.h"

namespace sixway::gpu {
namespace {

std::string mebibytes(uint64_t bytes) {
  return std::to_string(bytes >> 20) + " MiB";
}

// The process's mapped address space (the first field of /proc/self/statm, in pages); 0 when unknown.
uint64_t mappedBytes() {
  std::ifstream statm("/proc/self/statm");
  uint64_t pages = 0;
  if (!(statm >> pages)) return 0;
  return pages * uint64_t(sysconf(_SC_PAGESIZE));
}

}  // namespace

std::optional<std::string> addressSpaceShortfall(uint64_t limitBytes, uint64_t mappedBytes) {
  const uint64_t free = limitBytes > mappedBytes ? limitBytes - mappedBytes : 0;
  if (free >= kAddressSpaceHeadroomBytes) return std::nullopt;
  return "the address-space limit (ulimit -v) of " + mebibytes(limitBytes) + " leaves " + mebibytes(free) +
         " beside the " + mebibytes(mappedBytes) + " the Vulkan device maps; sixway needs " +
         mebibytes(kAddressSpaceHeadroomBytes) + " more (raise the limit to at least " +
         mebibytes(mappedBytes + kAddressSpaceHeadroomBytes) + ")";
}

void requireAddressSpaceHeadroom() {
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return;
  const uint64_t mapped = mappedBytes();
  if (mapped == 0) return;
  if (const auto shortfall = addressSpaceShortfall(uint64_t(limit.rlim_cur), mapped))
    throw GpuError(*shortfall);
}

}  // namespace sixway::gpu
