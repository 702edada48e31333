#include "gpu/bandwidth.h"

#include <algorithm>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/context.h"
#include "gpu/sequence.h"

namespace sixway::gpu {

double measureCopyBandwidth(const Context& context) {
  constexpr uint64_t kBytes = 64ull << 20;
  constexpr int kRepeats = 5;
  const Buffer source = Buffer::storage(context, kBytes, "bandwidth source");
  const Buffer destination = Buffer::storage(context, kBytes, "bandwidth destination");
  Sequence sequence(context, kRepeats + 1);
  for (int i = 0; i <= kRepeats; ++i) {  // the first copy warms up
    sequence.beginStage("copy");
    sequence.copy(source, destination);
    sequence.endStage();
  }
  sequence.submit();
  std::vector<double> gbPerSecond;
  for (size_t i = 1; i < sequence.stageTimes().size(); ++i)
    gbPerSecond.push_back(2.0 * double(kBytes) / (sequence.stageTimes()[i].milliseconds * 1e6));
  std::sort(gbPerSecond.begin(), gbPerSecond.end());
  return gbPerSecond[gbPerSecond.size() / 2];
}

}  // namespace sixway::gpu
