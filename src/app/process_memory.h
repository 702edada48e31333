#pragma once
// The process's own memory: for long-run checks (docs/robustness.md, "Long runs"), and under an address-space
// limit.
#include <cstdint>

namespace sixway::app {

// Resident set size in bytes (Linux /proc/self/statm); 0 where it cannot be read.
uint64_t residentSetBytes();

// Under an address-space limit (ulimit -v), one malloc arena for every thread, before any thread starts:
// glibc reserves 64 MiB of address space per thread's arena, lavapipe's threads take theirs some time after
// the device exists, and the device's mapping then varied by 2 arenas between runs (622-750 MiB), so the
// headroom check (gpu/address_space.h) could pass and the driver crash later. With one arena the mapping is
// the same in every run (366 MiB). No limit: nothing changes.
void oneMallocArenaUnderAddressLimit();

}  // namespace sixway::app
