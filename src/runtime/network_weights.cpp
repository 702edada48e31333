#include "runtime/network_weights.h"

#include "io/file_access.h"

namespace sixway::runtime {

io::SafetensorsFile readWeights(const std::filesystem::path& weights) {
  io::requireRegularFile(weights, "no such weights file");
  return io::readSafetensors(weights);
}

std::unique_ptr<nn::Network> loadNetwork(const gpu::Context& context, const gpu::PipelineCache& cache,
                                         const std::filesystem::path& weights, uint32_t size,
                                         const nn::NetworkOptions& options) {
  return std::make_unique<nn::Network>(context, cache, readWeights(weights), size, size, options);
}

}  // namespace sixway::runtime
