#include "gpu/bandwidth.h"

#include <algorithm>
#include <functional>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"

namespace sixway::gpu {
namespace {

constexpr uint64_t kBytes = 64ull << 20;
constexpr int kRepeats = 5;

// GB/s of the median of kRepeats copies recorded by `copy`, after one more that warms up.
double medianBandwidth(const Context& context, const std::function<void(Sequence&)>& copy) {
  Sequence sequence(context, kRepeats + 1);
  for (int i = 0; i <= kRepeats; ++i) {
    sequence.beginStage("copy");
    copy(sequence);
    sequence.endStage();
  }
  sequence.submit();
  std::vector<double> gbPerSecond;
  for (size_t i = 1; i < sequence.stageTimes().size(); ++i)
    gbPerSecond.push_back(2.0 * double(kBytes) / (sequence.stageTimes()[i].milliseconds * 1e6));
  std::sort(gbPerSecond.begin(), gbPerSecond.end());
  return gbPerSecond[gbPerSecond.size() / 2];
}

}  // namespace

double measureCopyBandwidth(const Context& context) {
  Buffer source = Buffer::storage(context, kBytes, "bandwidth source");
  Buffer destination = Buffer::storage(context, kBytes, "bandwidth destination");
  std::vector<uint32_t> pattern(kBytes / sizeof(uint32_t));
  for (size_t i = 0; i < pattern.size(); ++i) pattern[i] = uint32_t(i * 2654435761u);
  source.upload(pattern);
  const double transfer = medianBandwidth(context, [&](Sequence& s) { s.copy(source, destination); });

  destination.upload(std::vector<uint32_t>(pattern.size(), 0u));  // what the shader misses stays 0
  const PipelineCache cache(context);                             // one small shader: no cache file
  ComputePipelineDesc desc;
  desc.shader = "gpu/copy_words.comp";
  desc.bindings.assign(2, BindingType::StorageBuffer);
  desc.pushConstantBytes = sizeof(uint32_t);
  const Pipeline pipeline(context, cache, desc);
  const uint32_t words = uint32_t(kBytes / 16);
  const double shader = medianBandwidth(context, [&](Sequence& s) {
    s.dispatchLinear(pipeline, {reads(source), writes(destination)}, words, words, 256);
  });
  // A copy that skipped words would look faster than the memory is: the shader's copy must be exact.
  if (destination.download<uint32_t>() != pattern)
    throw GpuError("gpu/copy_words.comp did not copy the buffer exactly: no bandwidth measured");
  return std::max(transfer, shader);
}

}  // namespace sixway::gpu
