#pragma once
// SPIR-V of every shader in shaders/, embedded at build time.
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace sixway::shaders {

// Returns the SPIR-V words of `name` (its path below shaders/, e.g. "gpu/reduce_stats.comp").
// Throws std::runtime_error naming the shader when it was not built.
std::span<const uint32_t> spirv(std::string_view name);

// Every built shader's name, variants included (e.g. "nn/conv2d.comp:NN_FP16"), sorted.
std::vector<std::string_view> names();

}  // namespace sixway::shaders
