#pragma once
// The process's address-space limit (`ulimit -v`, RLIMIT_AS) against what a Vulkan driver needs: lavapipe's
// shader compiler (LLVM) crashes with SIGSEGV, not an error code, when an allocation fails while it builds a
// pipeline, so a limit that leaves too little room is refused up front with one line.
#include <cstdint>
#include <optional>
#include <string>

namespace sixway::gpu {

// Address space a command needs beside what the process maps once its device exists, measured on lavapipe
// (Mesa 22.3, 2 cores) with `sixway render` with a malloc arena per thread, its device mapping up to 750 MiB
// (the command line now keeps one arena under a limit: 366 MiB, app/process_memory.h): the 16² test plume
// crashed with 202 MiB to spare and ran with 226; the default scene (512², 64² maps) crashed with 324, failed
// with bad_alloc with 373 and ran with 397. Some smaller scenes would run with less: the bound is the default
// scene's.
constexpr uint64_t kAddressSpaceHeadroomBytes = uint64_t(448) << 20;

// The message refusing `limitBytes` of address space of which `mappedBytes` are mapped, or nothing when the
// rest is at least kAddressSpaceHeadroomBytes.
std::optional<std::string> addressSpaceShortfall(uint64_t limitBytes, uint64_t mappedBytes);

// Throws GpuError with that message when this process's RLIMIT_AS leaves too little; nothing without a limit
// or where /proc/self/statm cannot be read.
void requireAddressSpaceHeadroom();

}  // namespace sixway::gpu
