#include "sim/flags_schedule.h"

#include <cstring>

namespace sixway::sim {
namespace {

// What obstacles.comp reads: shapes, placements, the solid box, which inlets are active and where.
// Velocities, the inlets' smoke and the step number do not change a flag.
StepParams geometry(const StepParams& params) {
  StepParams g = params;
  for (GpuObstacle& o : g.obstacles) o.velocity = glm::vec4(0);
  for (GpuInlet& i : g.inlets) {
    i.velocity = glm::vec4(0);
    i.smoke = glm::vec4(0, 0, i.smoke.z, 0);
  }
  g.counts.z = g.counts.w = 0;
  return g;
}

bool same(const std::optional<StepParams>& a, const StepParams& b) {
  return a && std::memcmp(&*a, &b, sizeof(StepParams)) == 0;
}

}  // namespace

bool FlagsSchedule::needsPass(const StepParams& params) {
  const StepParams g = geometry(params);
  const bool needed = !(same(last_, g) && same(beforeLast_, g));
  beforeLast_ = last_;
  last_ = g;
  ++steps_;
  passes_ += needed;
  return needed;
}

}  // namespace sixway::sim
