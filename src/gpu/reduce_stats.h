#pragma once
// Summary statistics (sum, min, max, largest |value| and where, NaN/Inf count and the first one)
// of a float buffer, reduced on the GPU in a tree of passes. Used by the watchdog and the
// mass bookkeeping; only one small struct is read back.
#include <cstdint>
#include <memory>
#include <vector>

#include "gpu/buffer.h"

namespace sixway::gpu {

class Context;
class Pipeline;
class PipelineCache;
class Sequence;

// Mirrors `Stats` in shaders/common/stats.glsl (std430).
struct Stats {
  float sum;
  float minimum;
  float maximum;
  float maxAbs;
  uint32_t maxAbsIndex;
  uint32_t nonFinite;
  uint32_t firstNonFinite;  // 0xffffffff when every value is finite
  uint32_t count;
};
static_assert(sizeof(Stats) == 32);

// How the input buffer holds its values: value i is the float at i · stride, or with components > 1
// the length of the vector of that many floats there (e.g. a speed from vec4 velocities: {4, 3}).
struct ReduceInput {
  uint32_t stride = 1;
  uint32_t components = 1;
};

class ReduceStats {
 public:
  // Handles inputs of up to `maxCount` values.
  ReduceStats(const Context& context, const PipelineCache& cache, uint64_t maxCount, ReduceInput input = {});
  ~ReduceStats();

  // Records the passes that reduce the first `count` values of `values`.
  void record(Sequence& sequence, const Buffer& values, uint32_t count);
  // The result of the last submitted recording.
  Stats result() const;
  // Where the last recorded pass writes its Stats, e.g. for Sequence::addReadback.
  const Buffer& resultBuffer() const { return levels_[resultLevel_]; }

 private:
  static constexpr uint32_t kGroupSize = 256;
  static constexpr uint32_t kItemsPerThread = 8;
  static constexpr uint32_t kPerGroup = kGroupSize * kItemsPerThread;

  const Context* context_;
  ReduceInput input_;
  std::unique_ptr<Pipeline> fromValues_, fromStats_;
  std::vector<Buffer> levels_;  // levels_[i] holds the Stats written by pass i
  size_t resultLevel_ = 0;      // the level of the last recorded pass
};

}  // namespace sixway::gpu
