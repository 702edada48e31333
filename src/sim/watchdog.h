#pragma once
// Stops a diverging simulation with a message that names the step and the place, instead of
// letting NaN or runaway velocities turn into garbage frames.
#include <sixway/errors.h>
#include <glm/glm.hpp>
#include <string>

#include "gpu/reduce_stats.h"

namespace sixway::sim {

class WatchdogError : public Error {
 public:
  using Error::Error;
};

// Above this lattice speed (cells/step) the D3Q19 equilibrium, exact only to O(u²) with
// c_s = 1/√3 ≈ 0.577, is far outside its accurate range and the run is treated as diverged.
inline constexpr float kMaxStableLatticeSpeed = 0.35f;

struct WatchdogReport {
  bool tripped = false;
  std::string message;  // one line, empty when not tripped
};

// `speed` summarises |u| per lattice cell, `smoke` the smoke density per smoke cell.
WatchdogReport checkWatchdog(const gpu::Stats& speed, const gpu::Stats& smoke, uint64_t step,
                             glm::ivec3 lattice, glm::ivec3 smokeGrid, glm::vec3 origin, float cellSize);

}  // namespace sixway::sim
