#include "sim/watchdog.h"

#include <cstdio>

namespace sixway::sim {
namespace {

std::string where(uint32_t index, glm::ivec3 grid, glm::vec3 origin, float cellSize) {
  const glm::ivec3 c(index % grid.x, (index / grid.x) % grid.y, index / (grid.x * grid.y));
  const glm::vec3 p = origin + (glm::vec3(c) + 0.5f) * cellSize;
  char text[128];
  std::snprintf(text, sizeof(text), "cell (%d, %d, %d) at (%.3g, %.3g, %.3g) m", c.x, c.y, c.z, p.x, p.y,
                p.z);
  return text;
}

}  // namespace

WatchdogReport checkWatchdog(const gpu::Stats& speed, const gpu::Stats& smoke, uint64_t step,
                             glm::ivec3 lattice, glm::ivec3 smokeGrid, glm::vec3 origin, float cellSize) {
  const std::string when = "watchdog: by step " + std::to_string(step) + ", ";
  if (speed.nonFinite > 0)
    return {true, when + "the velocity is NaN or infinite in " + std::to_string(speed.nonFinite) +
                      " cells, first " + where(speed.firstNonFinite, lattice, origin, cellSize)};
  if (speed.maxAbs > kMaxStableLatticeSpeed) {
    char value[64];
    std::snprintf(value, sizeof(value), "%.3f", speed.maxAbs);
    return {true, when + "the lattice speed reached " + value + " cells/step (stable limit " +
                      std::to_string(kMaxStableLatticeSpeed).substr(0, 4) + ") at " +
                      where(speed.maxAbsIndex, lattice, origin, cellSize) +
                      "; lower the inflow speed or fluid.max_lattice_velocity"};
  }
  const float smokeCell = cellSize * float(lattice.x) / float(smokeGrid.x);
  if (smoke.nonFinite > 0)
    return {true, when + "the smoke density is NaN or infinite in " + std::to_string(smoke.nonFinite) +
                      " cells, first " + where(smoke.firstNonFinite, smokeGrid, origin, smokeCell)};
  return {};
}

}  // namespace sixway::sim
