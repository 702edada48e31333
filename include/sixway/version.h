#pragma once
/* The version of sixway's headers, and of the library linked (which an engine compares at start: a program
 * built against one version's headers must link the same version). The build reads the numbers from here.
 * C and C++ (the C API's sixwayVersion() is in sixway.h). */

#define SIXWAY_VERSION_MAJOR 0
#define SIXWAY_VERSION_MINOR 1
#define SIXWAY_VERSION_PATCH 0
/* major · 10000 + minor · 100 + patch, for #if comparisons. */
#define SIXWAY_VERSION (SIXWAY_VERSION_MAJOR * 10000 + SIXWAY_VERSION_MINOR * 100 + SIXWAY_VERSION_PATCH)

#ifdef __cplusplus
#include <cstdint>

namespace sixway {

struct Version {
  uint32_t major, minor, patch;
};

// The version of the library linked; equal to the headers' SIXWAY_VERSION_* in a consistent build.
Version version();

}  // namespace sixway
#endif
