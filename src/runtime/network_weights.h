#pragma once
// A network's weights file (docs/network-format.md), read and checked the same way by the runtime and by
// every tool: a missing one is "FILE: no such weights file", a malformed one an io::InputError naming it.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>

#include "io/safetensors.h"
#include "nn/network.h"

namespace sixway::gpu {
class Context;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::runtime {

io::SafetensorsFile readWeights(const std::filesystem::path& weights);
// A weights file's bytes held by the engine; `name` names them in errors ("weights in memory" when empty).
io::SafetensorsFile readWeights(std::span<const std::byte> bytes, const std::filesystem::path& name);

// The network of `weights` for size × size guides.
std::unique_ptr<nn::Network> loadNetwork(const gpu::Context& context, const gpu::PipelineCache& cache,
                                         const io::SafetensorsFile& weights, uint32_t size,
                                         const nn::NetworkOptions& options);

}  // namespace sixway::runtime
