#include "gpu/address_space.h"

#include "gpu/check.h"
#include "platform/platform.h"

namespace sixway::gpu {
namespace {

std::string mebibytes(uint64_t bytes) {
  return std::to_string(bytes >> 20) + " MiB";
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
  const std::optional<uint64_t> limit = platform::addressSpaceLimit();
  const uint64_t mapped = platform::mappedBytes();
  if (!limit || mapped == 0) return;
  if (const auto shortfall = addressSpaceShortfall(*limit, mapped)) throw GpuError(*shortfall);
}

}  // namespace sixway::gpu
