#include "gpu/reduce_stats.h"

#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/gpu_spec.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"

namespace sixway::gpu {
namespace {

uint64_t groupsFor(uint64_t count, uint32_t perGroup) {
  return (count + perGroup - 1) / perGroup;
}

}  // namespace

ReduceStats::ReduceStats(const Context& context, const PipelineCache& cache, uint64_t maxCount,
                         ReduceInput input)
    : context_(&context), input_(input) {
  if (maxCount == 0 || maxCount > UINT32_MAX)
    throw GpuError("ReduceStats: count must be 1.." + std::to_string(UINT32_MAX));
  if (input.stride < input.components || input.components == 0)
    throw GpuError("ReduceStats: a stride of " + std::to_string(input.stride) + " cannot hold " +
                   std::to_string(input.components) + " components");
  auto desc = [input](bool fromStats) {
    ComputePipelineDesc d;
    d.shader = "gpu/reduce_stats.comp";
    d.bindings = {BindingType::StorageBuffer, BindingType::StorageBuffer, BindingType::StorageBuffer};
    d.pushConstantBytes = sizeof(uint32_t);
    d.spec.set(spec::kGroupSize, kGroupSize).set(spec::kItemsPerThread, kItemsPerThread);
    d.spec.set(spec::kFromStats, fromStats)
        .set(spec::kStride, input.stride)
        .set(spec::kComponents, input.components);
    return d;
  };
  fromValues_ = std::make_unique<Pipeline>(context, cache, desc(false));
  fromStats_ = std::make_unique<Pipeline>(context, cache, desc(true));
  for (uint64_t n = groupsFor(maxCount, kPerGroup);; n = groupsFor(n, kPerGroup)) {
    levels_.push_back(
        Buffer::storage(context, n * sizeof(Stats), "reduction level " + std::to_string(levels_.size())));
    if (n == 1) break;
  }
}

ReduceStats::~ReduceStats() = default;

void ReduceStats::record(Sequence& sequence, const Buffer& values, uint32_t count) {
  if (count == 0 || (uint64_t(count - 1) * input_.stride + input_.components) * sizeof(float) > values.size())
    throw GpuError("ReduceStats: " + std::to_string(count) + " values asked of " + values.name());
  // Pass i reduces counts[i] inputs into counts[i+1] = ceil(counts[i] / kPerGroup) Stats in levels_[i];
  // a single value still takes one pass.
  std::vector<uint32_t> counts = {count};
  do counts.push_back(static_cast<uint32_t>(groupsFor(counts.back(), kPerGroup)));
  while (counts.back() > 1);
  const size_t passes = counts.size() - 1;
  if (passes > levels_.size())
    throw GpuError("ReduceStats: " + std::to_string(count) + " values exceed its capacity");
  for (size_t pass = 0; pass < passes; ++pass) {
    // The binding the pass does not read is given a buffer it may alias harmlessly (read-only).
    const Binding statsIn = pass == 0 ? reads(values) : reads(levels_[pass - 1]);
    sequence.dispatch(pass == 0 ? *fromValues_ : *fromStats_, {reads(values), statsIn, writes(levels_[pass])},
                      counts[pass], counts[pass + 1]);
  }
  resultLevel_ = passes - 1;
}

Stats ReduceStats::result() const {
  Stats stats;
  levels_[resultLevel_].download(std::as_writable_bytes(std::span(&stats, 1)));
  return stats;
}

}  // namespace sixway::gpu
