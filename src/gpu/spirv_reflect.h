#pragma once
// The specialization constants a SPIR-V module declares, read from its words: what gpu::Pipeline checks
// the host's SpecConstants against.
#include <cstdint>
#include <map>
#include <span>
#include <string>

#include "gpu/spec_id.h"

namespace sixway::gpu {

struct ShaderSpecConstant {
  SpecType type;
  std::string name;  // empty for a workgroup size (local_size_x_id, ...): glslang names none
};

// By SpecId. Throws GpuError when `words` is not a well-formed SPIR-V module.
std::map<uint32_t, ShaderSpecConstant> reflectSpecConstants(std::span<const uint32_t> words);

}  // namespace sixway::gpu
