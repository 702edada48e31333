// Pipeline creation refuses specialization constants the shader does not declare: an id it lacks, another
// name at the id, another type. The error names the shader and the id.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "gpu/check.h"
#include "gpu/gpu_spec.h"
#include "gpu/pipeline.h"
#include "support/gpu_fixture.h"

namespace sixway::test {
namespace {

using ::testing::HasSubstr;

class PipelineSpecTest : public GpuTest {
 protected:
  // The message of the GpuError that creating texel_buffer_scale.comp's pipeline with `spec` throws.
  std::string computeError(const gpu::SpecConstants& spec) {
    gpu::ComputePipelineDesc desc{"gpu/texel_buffer_scale.comp",
                                  {gpu::BindingType::StorageTexelBuffer, gpu::BindingType::StorageBuffer},
                                  sizeof(uint32_t),
                                  spec};
    try {
      gpu::Pipeline pipeline(context(), pipelineCache(), desc);
    } catch (const gpu::GpuError& e) {
      return e.what();
    }
    ADD_FAILURE() << "the pipeline was created";
    return {};
  }
  // The same for fill_gradient.vert and fill_gradient.frag.
  std::string graphicsError(const gpu::SpecConstants& spec) {
    gpu::GraphicsPipelineDesc desc;
    desc.vertexShader = "gpu/fill_gradient.vert";
    desc.fragmentShader = "gpu/fill_gradient.frag";
    desc.spec = spec;
    desc.colorFormats = {VK_FORMAT_R32G32B32A32_SFLOAT};
    try {
      gpu::Pipeline pipeline(context(), pipelineCache(), desc);
    } catch (const gpu::GpuError& e) {
      return e.what();
    }
    ADD_FAILURE() << "the pipeline was created";
    return {};
  }
};

TEST_F(PipelineSpecTest, AnIdTheShaderLacksIsRefused) {
  EXPECT_EQ(computeError(gpu::SpecConstants().set({7, "SCALE"}, 2.0f)),
            "shader gpu/texel_buffer_scale.comp has no specialization constant 7 (set by the host as SCALE)");
}

TEST_F(PipelineSpecTest, AnotherNameAtTheIdIsRefused) {
  EXPECT_EQ(
      computeError(gpu::SpecConstants().set({0, "OFFSET"}, 2.0f)),
      "shader gpu/texel_buffer_scale.comp: specialization constant 0 is SCALE, set by the host as OFFSET");
}

TEST_F(PipelineSpecTest, AnotherTypeIsRefused) {
  EXPECT_EQ(
      computeError(gpu::SpecConstants().set(gpu::spec::kScale, 2u)),
      "shader gpu/texel_buffer_scale.comp: specialization constant 0 (SCALE) is float in the shader, set "
      "by the host as uint");
  EXPECT_THAT(computeError(gpu::SpecConstants().set(gpu::spec::kScale, 2)),
              HasSubstr("set by the host as int"));
  EXPECT_THAT(computeError(gpu::SpecConstants().set(gpu::spec::kScale, true)),
              HasSubstr("set by the host as bool"));
}

TEST_F(PipelineSpecTest, AGraphicsPipelineLooksInBothStages) {
  // BLUE is the fragment shader's; the vertex shader has none.
  EXPECT_EQ(
      graphicsError(gpu::SpecConstants().set(gpu::spec::kBlue, 0.5f).set({1, "RED"}, 0.5f)),
      "shaders gpu/fill_gradient.vert and gpu/fill_gradient.frag have no specialization constant 1 (set by "
      "the host as RED)");
  EXPECT_EQ(
      graphicsError(gpu::SpecConstants().set(gpu::spec::kBlue, 1)),
      "shader gpu/fill_gradient.frag: specialization constant 0 (BLUE) is float in the shader, set by the "
      "host as int");
}

}  // namespace
}  // namespace sixway::test
