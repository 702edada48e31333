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

nn::NetworkOptions sceneNetworkOptions(const io::Scene& scene, bool fp16) {
  nn::NetworkOptions options;
  options.precision = fp16 ? nn::Precision::Fp16 : nn::Precision::Fp32;
  options.emission = scene.smoke.emission.intensity > 0.0f;
  options.albedo = scene.smoke.albedo;
  return options;
}

}  // namespace sixway::runtime
