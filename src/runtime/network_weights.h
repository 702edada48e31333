#pragma once
// A network's weights file (docs/network-format.md), read and checked the same way by the runtime and by
// every tool: a missing one is "FILE: no such weights file", a malformed one an io::InputError naming it.
#include <cstdint>
#include <filesystem>
#include <memory>

#include "io/safetensors.h"
#include "nn/network.h"

namespace sixway::gpu {
class Context;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::runtime {

io::SafetensorsFile readWeights(const std::filesystem::path& weights);

// The network of `weights` for size × size guides.
std::unique_ptr<nn::Network> loadNetwork(const gpu::Context& context, const gpu::PipelineCache& cache,
                                         const std::filesystem::path& weights, uint32_t size,
                                         const nn::NetworkOptions& options);

}  // namespace sixway::runtime
