#pragma once
// SPIR-V of every shader in shaders/, embedded at build time.
#include <cstdint>
#include <span>
#include <string_view>

namespace sixway::shaders {

// Returns the SPIR-V words of `name` (its path below shaders/, e.g. "gpu/reduce_stats.comp").
// Throws std::runtime_error naming the shader when it was not built.
std::span<const uint32_t> spirv(std::string_view name);

}  // namespace sixway::shaders
