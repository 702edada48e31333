// The memory ceiling of the LBM step on a device (docs/benchmarks.md, "Simulation"): the bandwidth of
// shaders/sim/stream_bound.comp (the step's 19 gathers and 19 stores per cell, nothing else; and the same
// traffic without the neighbour offsets) next to a plain buffer copy, for the two benchmark lattices. Not a
// test. Usage: stream_bound_bench [REPEATS]
#include <algorithm>
#include <cstdio>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "gpu/bandwidth.h"
#include "gpu/buffer.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "sim/sim_spec.h"

using namespace sixway;

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::stoi(argv[1]) : 10;
  gpu::Context context(gpu::ContextOptions{});
  gpu::PipelineCache cache(context, gpu::defaultPipelineCacheFile(context));
  const double copy = gpu::measureCopyBandwidth(context);
  std::printf("%s: buffer copy %.1f GB/s\n", context.properties().deviceName, copy);
  for (const bool pull : {true, false})
    for (const glm::ivec3 size : {glm::ivec3(64, 128, 64), glm::ivec3(128, 256, 128)}) {
      const uint64_t cells = uint64_t(size.x) * size.y * size.z;
      std::vector<gpu::Buffer> lattices;
      for (int b = 0; b < 8; ++b)
        lattices.push_back(
            gpu::Buffer::storage(context, cells * 5 * sizeof(float), "lattice " + std::to_string(b)));
      gpu::ComputePipelineDesc desc;
      desc.shader = "sim/stream_bound.comp";
      desc.bindings.assign(8, gpu::BindingType::StorageBuffer);
      for (int a = 0; a < 3; ++a) desc.spec.set(sim::spec::kSize[a], size[a]);
      desc.spec.set(sim::spec::kPull, pull);
      const gpu::Pipeline pipeline(context, cache, desc);
      gpu::Sequence sequence(context, uint32_t(repeats + 1));
      for (int r = 0; r <= repeats; ++r) {  // the first one warms up
        const int from = (r % 2) * 4, to = 4 - from;
        std::vector<gpu::Binding> bindings;
        for (int b = 0; b < 4; ++b) bindings.push_back(gpu::reads(lattices[from + b]));
        for (int b = 0; b < 4; ++b) bindings.push_back(gpu::writes(lattices[to + b]));
        sequence.beginStage("stream");
        sequence.dispatchLinear(pipeline, bindings, std::span<const std::byte>(), cells, 64);
        sequence.endStage();
      }
      sequence.finish();
      sequence.submit();
      std::vector<double> ms;
      for (size_t i = 1; i < sequence.stageTimes().size(); ++i)
        ms.push_back(sequence.stageTimes()[i].milliseconds);
      std::sort(ms.begin(), ms.end());
      const double median = ms[ms.size() / 2];
      const double gbs = double(cells) * 19 * 2 * sizeof(float) / (median * 1e6);
      std::printf("%s %dx%dx%d: %.2f ms per update, %.1f MLUPs, %.2f GB/s = %.1f%% of the copy bandwidth\n",
                  pull ? "pull-streaming" : "in place", size.x, size.y, size.z, median,
                  double(cells) / (median * 1e3), gbs, 100.0 * gbs / copy);
    }
}
