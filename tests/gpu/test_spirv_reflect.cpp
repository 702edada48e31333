// The specialization constants read from a module's SPIR-V: ids, types (signedness and width from OpTypeInt),
// and names, on shaders built into sixway.
#include <gtest/gtest.h>

#include <sixway/shader_registry.h>
#include <vector>

#include "gpu/check.h"
#include "gpu/spirv_reflect.h"

namespace sixway::test {
namespace {

using gpu::SpecType;

void expectConstant(const std::map<uint32_t, gpu::ShaderSpecConstant>& constants, uint32_t id, SpecType type,
                    const std::string& name) {
  const auto constant = constants.find(id);
  ASSERT_NE(constant, constants.end()) << id;
  EXPECT_EQ(gpu::specTypeName(constant->second.type), gpu::specTypeName(type)) << id;
  EXPECT_EQ(constant->second.name, name) << id;
}

TEST(SpirvReflect, ReadsTheIdTypeAndNameOfEachConstant) {
  const auto constants = gpu::reflectSpecConstants(shaders::spirv("gpu/reduce_stats.comp"));
  EXPECT_EQ(constants.size(), 5u);
  expectConstant(constants, 0, SpecType::Uint,
                 "");  // local_size_x_id: unnamed, and declared twice by glslang
  expectConstant(constants, 1, SpecType::Uint, "ITEMS_PER_THREAD");
  expectConstant(constants, 2, SpecType::Bool, "FROM_STATS");
  expectConstant(constants, 3, SpecType::Uint, "STRIDE");
  expectConstant(constants, 4, SpecType::Uint, "COMPONENTS");
}

TEST(SpirvReflect, TellsSignedIntFromUintAndFloat) {
  const auto guide = gpu::reflectSpecConstants(shaders::spirv("render/guide_lightmaps.comp"));
  EXPECT_EQ(guide.size(), 1u);
  expectConstant(guide, 0, SpecType::Int, "kGuideLights");
  const auto scale = gpu::reflectSpecConstants(shaders::spirv("gpu/texel_buffer_scale.comp"));
  EXPECT_EQ(scale.size(), 1u);
  expectConstant(scale, 0, SpecType::Float, "SCALE");
}

TEST(SpirvReflect, AShaderWithoutConstantsHasNone) {
  EXPECT_TRUE(gpu::reflectSpecConstants(shaders::spirv("sim/voxelize_mesh.comp")).empty());
}

TEST(SpirvReflect, RefusesWhatIsNotSpirv) {
  const std::vector<uint32_t> text = {0x6c6f6568, 0x6f77206c, 0x00646c72, 0, 0, 0};
  EXPECT_THROW(gpu::reflectSpecConstants(text), gpu::GpuError);
  // A module cut off within an instruction.
  const auto spirv = shaders::spirv("gpu/reduce_stats.comp");
  std::vector<uint32_t> cut(spirv.begin(), spirv.begin() + 6);
  cut[5] = (9u << 16) | 5u;  // an OpName of 9 words, 1 of them present
  EXPECT_THROW(gpu::reflectSpecConstants(cut), gpu::GpuError);
}

}  // namespace
}  // namespace sixway::test
