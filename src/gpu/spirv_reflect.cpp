#include "gpu/spirv_reflect.h"

#include <cstring>

#include "gpu/check.h"

namespace sixway::gpu {
namespace {

// From the SPIR-V specification (spirv.h), the few opcodes and the decoration this reads.
constexpr uint32_t kMagic = 0x07230203;
constexpr uint32_t kHeaderWords = 5;
constexpr uint32_t kOpName = 5;
constexpr uint32_t kOpTypeBool = 20;
constexpr uint32_t kOpTypeInt = 21;
constexpr uint32_t kOpTypeFloat = 22;
constexpr uint32_t kOpSpecConstantTrue = 48;
constexpr uint32_t kOpSpecConstantFalse = 49;
constexpr uint32_t kOpSpecConstant = 50;
constexpr uint32_t kOpDecorate = 71;
constexpr uint32_t kDecorationSpecId = 1;

// A literal string: UTF-8 bytes, nul-terminated, padded to whole words.
std::string literalString(std::span<const uint32_t> words) {
  std::string bytes(words.size() * sizeof(uint32_t), '\0');
  std::memcpy(bytes.data(), words.data(), bytes.size());
  return bytes.substr(0, bytes.find('\0'));
}

SpecType scalarType(uint32_t opcode, std::span<const uint32_t> operands) {
  if (opcode == kOpTypeBool) return SpecType::Bool;
  if (operands[1] != 32) return SpecType::Other;  // width
  if (opcode == kOpTypeFloat) return SpecType::Float;
  return operands[2] ? SpecType::Int : SpecType::Uint;  // signedness
}

}  // namespace

std::map<uint32_t, ShaderSpecConstant> reflectSpecConstants(std::span<const uint32_t> words) {
  if (words.size() < kHeaderWords || words[0] != kMagic) throw GpuError("not a SPIR-V module");
  std::map<uint32_t, uint32_t> specIdOf;   // result id → SpecId
  std::map<uint32_t, std::string> nameOf;  // result id → OpName
  std::map<uint32_t, SpecType> typeOf;     // result id of a scalar type → its type
  std::map<uint32_t, uint32_t> typeIdOf;   // result id of a specialization constant → its type's
  for (size_t at = kHeaderWords; at < words.size();) {
    const uint32_t wordCount = words[at] >> 16, opcode = words[at] & 0xffff;
    if (wordCount == 0 || at + wordCount > words.size())
      throw GpuError("SPIR-V instruction at word " + std::to_string(at) + " runs past the module's end");
    const std::span<const uint32_t> operands = words.subspan(at + 1, wordCount - 1);
    at += wordCount;
    if (opcode == kOpName && !operands.empty()) {
      nameOf[operands[0]] = literalString(operands.subspan(1));
    } else if (opcode == kOpDecorate && operands.size() >= 3 && operands[1] == kDecorationSpecId) {
      specIdOf[operands[0]] = operands[2];
    } else if ((opcode == kOpTypeBool && operands.size() >= 1) ||
               (opcode == kOpTypeFloat && operands.size() >= 2) ||
               (opcode == kOpTypeInt && operands.size() >= 3)) {
      typeOf[operands[0]] = scalarType(opcode, operands);
    } else if ((opcode == kOpSpecConstantTrue || opcode == kOpSpecConstantFalse ||
                opcode == kOpSpecConstant) &&
               operands.size() >= 2) {
      typeIdOf[operands[1]] = operands[0];
    }
  }
  std::map<uint32_t, ShaderSpecConstant> constants;
  for (const auto& [result, specId] : specIdOf) {
    const auto typeId = typeIdOf.find(result);
    if (typeId == typeIdOf.end()) continue;  // not on an OpSpecConstant*: invalid SPIR-V, ignored
    const auto type = typeOf.find(typeId->second);
    const auto name = nameOf.find(result);
    // glslang declares a workgroup size's constant twice, alike and unnamed: one is kept.
    constants.try_emplace(specId, ShaderSpecConstant{type == typeOf.end() ? SpecType::Other : type->second,
                                                     name == nameOf.end() ? std::string() : name->second});
  }
  return constants;
}

}  // namespace sixway::gpu
