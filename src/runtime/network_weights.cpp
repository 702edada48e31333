#include "runtime/network_weights.h"

#include "io/file_access.h"

namespace sixway::runtime {

io::SafetensorsFile readWeights(const std::filesystem::path& weights) {
  io::requireRegularFile(weights, "no such weights file");
  return io::readSafetensors(weights);
}

io::SafetensorsFile readWeights(std::span<const std::byte> bytes, const std::filesystem::path& name) {
  return io::parseSafetensors(std::span(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()),
                              name.empty() ? std::filesystem::path("weights in memory") : name);
}

std::unique_ptr<nn::Network> loadNetwork(const gpu::Context& context, const gpu::PipelineCache& cache,
                                         const io::SafetensorsFile& weights, uint32_t size,
                                         const nn::NetworkOptions& options) {
  return std::make_unique<nn::Network>(context, cache, weights, size, size, options);
}

}  // namespace sixway::runtime
