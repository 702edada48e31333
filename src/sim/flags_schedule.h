#pragma once
// When the cell flags must be computed again. obstacles.comp writes, for step s, each cell's obstacle and
// inlet from the geometry of step s and keeps the obstacle of step s − 1 (FLAG_PREVIOUS): when the geometry
// of s is that of s − 1 and s − 2, the flags buffer already holds what the pass would write, and the step
// skips it (its indirect dispatch gets zero groups). Static obstacles and steady inlets then cost two passes
// in all.
#include <cstdint>
#include <optional>

#include "sim/sim_params.h"

namespace sixway::sim {

class FlagsSchedule {
 public:
  // Steps in the order they run (the order their parameters are filled): whether step `params` needs the
  // pass.
  bool needsPass(const StepParams& params);
  // The geometry changed where StepParams cannot show it (a mesh's voxels): the next two steps run the pass.
  void invalidate() { last_.reset(), beforeLast_.reset(); }
  uint64_t passes() const { return passes_; }  // steps that ran the pass
  uint64_t steps() const { return steps_; }

 private:
  std::optional<StepParams> last_, beforeLast_;  // the geometry of the two previous steps
  uint64_t passes_ = 0, steps_ = 0;
};

}  // namespace sixway::sim
