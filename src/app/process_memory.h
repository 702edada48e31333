#pragma once
// The process's own memory, for long-run checks (docs/robustness.md, "Long runs").
#include <cstdint>

namespace sixway::app {

// Resident set size in bytes (Linux /proc/self/statm); 0 where it cannot be read.
uint64_t residentSetBytes();

}  // namespace sixway::app
