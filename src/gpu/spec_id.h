#pragma once
// How the host names a specialization constant. Each shader family defines its ids once, in
// shaders/common/<family>_spec.glsl and in a C++ header beside its host code (src/sim/sim_spec.h, ...);
// gpu::Pipeline checks every id it is given against the shader's SPIR-V (spirv_reflect.h).
#include <cstdint>
#include <string_view>

namespace sixway::gpu {

struct SpecId {
  uint32_t id;            // the constant_id
  std::string_view name;  // the constant's name in the shader (GLSL names no local_size_*_id constant)
};

// A specialization constant's type: the 32-bit ones the host sets, or any other the shader declares.
enum class SpecType { Bool, Int, Uint, Float, Other };

constexpr std::string_view specTypeName(SpecType type) {
  switch (type) {
    case SpecType::Bool:
      return "bool";
    case SpecType::Int:
      return "int";
    case SpecType::Uint:
      return "uint";
    case SpecType::Float:
      return "float";
    case SpecType::Other:
      break;
  }
  return "not a 32-bit bool, int, uint or float";
}

}  // namespace sixway::gpu
