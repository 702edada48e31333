// Resources beyond the device's limits are refused before allocation, with what to reduce.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "gpu/buffer.h"
#include "gpu/check.h"
#include "gpu/gpu_spec.h"
#include "gpu/image.h"
#include "gpu/pipeline.h"
#include "gpu/reduce_stats.h"
#include "gpu/sequence.h"
#include "support/gpu_fixture.h"

namespace sixway::test {
namespace {

using ::testing::HasSubstr;

class LimitsTest : public GpuTest {};

TEST_F(LimitsTest, StorageBufferBeyondTheBindableRangeIsRefused) {
  const uint64_t tooBig = uint64_t(context().limits().maxStorageBufferRange) + 4;
  try {
    gpu::Buffer buffer = gpu::Buffer::storage(context(), tooBig, "density grid");
    FAIL() << "no error";
  } catch (const gpu::LimitError& e) {  // a GpuError, whose problem() callers can rephrase
    EXPECT_THAT(e.what(), HasSubstr("density grid needs a storage buffer of"));
    EXPECT_THAT(e.what(), HasSubstr("reduce its size"));
    EXPECT_EQ(e.problem() + "; reduce its size", e.what());
  }
}

TEST_F(LimitsTest, ImageLargerThanTheDeviceAllowsIsRefused) {
  const uint32_t side = context().limits().maxImageDimension2D + 1;
  try {
    gpu::Image image(context(),
                     {side, 4, 1, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_STORAGE_BIT, "lightmap"});
    FAIL() << "no error";
  } catch (const gpu::LimitError& e) {
    EXPECT_THAT(e.what(), HasSubstr("lightmap: image of"));
    EXPECT_THAT(e.what(), HasSubstr("reduce its size"));
  }
}

TEST_F(LimitsTest, AnyBufferBeyondTheDeviceHeapIsRefused) {
  const uint64_t tooBig = context().capabilities().deviceLocalHeapBytes + 4;
  EXPECT_THROW(gpu::Buffer(context(), tooBig, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, gpu::MemoryKind::HostUpload,
                           "staging"),
               gpu::LimitError);
  const uint32_t side = context().limits().maxImageDimension3D;
  EXPECT_THROW(gpu::Image(context(), {side, side, side, VK_FORMAT_R32G32B32A32_SFLOAT,
                                      VK_IMAGE_USAGE_STORAGE_BIT, "volume"}),
               gpu::LimitError);
}

TEST_F(LimitsTest, EmptyBufferIsRefused) {
  EXPECT_THROW(gpu::Buffer::storage(context(), 0, "nothing"), gpu::GpuError);
}

TEST_F(LimitsTest, DispatchMismatchesAreRefusedWhileRecording) {
  gpu::ComputePipelineDesc desc;
  desc.shader = "gpu/reduce_stats.comp";
  desc.bindings = {gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer,
                   gpu::BindingType::StorageBuffer};
  desc.pushConstantBytes = 4;
  desc.spec.set(gpu::spec::kGroupSize, 64u);
  gpu::Pipeline pipeline(context(), pipelineCache(), desc);
  gpu::Buffer buffer = gpu::Buffer::storage(context(), 1024, "b");
  gpu::Sequence sequence(context());
  const uint32_t count = 1;
  EXPECT_THROW(sequence.dispatch(pipeline, {gpu::reads(buffer)}, count, 1),
               gpu::GpuError);  // 1 of 3 bindings
  const uint64_t wrongPush = 0;
  EXPECT_THROW(sequence.dispatch(pipeline, {gpu::reads(buffer), gpu::reads(buffer), gpu::writes(buffer)},
                                 wrongPush, 1),
               gpu::GpuError);
  const uint32_t tooMany = context().limits().maxComputeWorkGroupCount[0] + 1;
  EXPECT_THROW(sequence.dispatch(pipeline, {gpu::reads(buffer), gpu::reads(buffer), gpu::writes(buffer)},
                                 count, tooMany),
               gpu::GpuError);
}

TEST_F(LimitsTest, UnknownShaderNameIsAnError) {
  gpu::ComputePipelineDesc desc;
  desc.shader = "gpu/no_such_shader.comp";
  EXPECT_THROW(gpu::Pipeline(context(), pipelineCache(), desc), std::runtime_error);
}

}  // namespace
}  // namespace sixway::test
