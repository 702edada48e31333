// The Vulkan host: device selection, validation, buffers, images, recorded sequences.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <random>

#include "gpu/buffer.h"
#include "gpu/check.h"
#include "gpu/image.h"
#include "gpu/reduce_stats.h"
#include "gpu/sequence.h"
#include "support/gpu_fixture.h"

namespace sixway::test {
namespace {

using ::testing::HasSubstr;

class ContextTest : public GpuTest {};

TEST_F(ContextTest, OpensAVulkan13DeviceWithWhatTheStagesNeed) {
  const gpu::Context& ctx = context();
  EXPECT_GE(ctx.properties().apiVersion, VK_API_VERSION_1_3);
  EXPECT_NE(ctx.cmdPushDescriptorSet, nullptr);
  EXPECT_TRUE(ctx.validationEnabled());
  EXPECT_TRUE(ctx.capabilities().timestamps);
  EXPECT_GT(ctx.capabilities().deviceLocalHeapBytes, 0u);
  EXPECT_GE(ctx.limits().maxStorageBufferRange, 128u << 20);
}

TEST_F(ContextTest, ValidationLayerCatchesMisuse) {
  // An undefined flag bit: the layer must report it, which proves a test can fail on validation.
  VkFenceCreateInfo info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  info.flags = 0x40000000u;
  VkFence fence = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateFence(context().device(), &info, nullptr, &fence), VK_SUCCESS);
  vkDestroyFence(context().device(), fence, nullptr);
  EXPECT_GE(context().validationMessageCount(), 1u);
  EXPECT_THAT(context().validationLog()->messages().front(), HasSubstr("flags"));
  forgetValidationMessages();
}

TEST(ContextSelection, OutOfRangeDeviceIndexIsAClearError) {
  gpu::ContextOptions options;
  options.deviceIndex = 99;
  try {
    gpu::Context context(options);
    FAIL() << "no error";
  } catch (const gpu::GpuError& e) {
    EXPECT_THAT(e.what(), HasSubstr("--device 99: no such device"));
  }
}

// Device numbers out of range are errors, not wrapped: 99999999999999999999 must not read as "--device -1",
// nor 4294967296 wrap to 0.
TEST(ContextSelection, MalformedEnvironmentDeviceIsAClearError) {
  for (const char* value : {"first", "99999999999999999999", "4294967296", "-1"}) {
    setenv("SIXWAY_DEVICE", value, 1);
    try {
      gpu::Context context;
      ADD_FAILURE() << "no error for " << value;
    } catch (const gpu::GpuError& e) {
      EXPECT_THAT(e.what(),
                  HasSubstr(std::string("SIXWAY_DEVICE: expected a device index, got '") + value + "'"));
    }
  }
  unsetenv("SIXWAY_DEVICE");
}

TEST(ContextSelection, AnEnvironmentIndexWithNoDeviceNamesTheVariable) {
  setenv("SIXWAY_DEVICE", "7", 1);
  try {
    gpu::Context context;
    ADD_FAILURE() << "no error";
  } catch (const gpu::GpuError& e) {
    EXPECT_THAT(e.what(), HasSubstr("SIXWAY_DEVICE=7: no such device"));
  }
  unsetenv("SIXWAY_DEVICE");
}

TEST(ContextSelection, EnvironmentPicksTheDevice) {
  setenv("SIXWAY_DEVICE", "0", 1);
  gpu::Context context;
  EXPECT_NE(context.device(), VK_NULL_HANDLE);
  unsetenv("SIXWAY_DEVICE");
}

class BufferTest : public GpuTest {};

TEST_F(BufferTest, DeviceBufferRoundTripsThroughStaging) {
  std::vector<uint32_t> values(10007);
  std::iota(values.begin(), values.end(), 17u);
  gpu::Buffer buffer = gpu::Buffer::storage(context(), values.size() * 4, "round trip");
  buffer.upload(values);
  EXPECT_EQ(buffer.download<uint32_t>(), values);

  std::vector<uint32_t> patch = {1, 2, 3};
  buffer.upload(std::as_bytes(std::span(patch)), 40);
  std::vector<uint32_t> read(5);
  buffer.download(std::as_writable_bytes(std::span(read)), 36);
  EXPECT_EQ(read, (std::vector<uint32_t>{values[9], 1, 2, 3, values[13]}));
}

TEST_F(BufferTest, OutOfBoundsUploadIsRefused) {
  gpu::Buffer buffer = gpu::Buffer::storage(context(), 64, "small");
  std::vector<uint32_t> tooMany(17);
  EXPECT_THROW(buffer.upload(tooMany), gpu::GpuError);
}

class ImageTest : public GpuTest {};

TEST_F(ImageTest, TwoDimensionalRgbaRoundTrips) {
  gpu::Image image(context(), {37, 23, 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                               VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "rgba"});
  std::vector<float> texels(37 * 23 * 4);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> uniform(-2.0f, 2.0f);
  for (float& t : texels) t = uniform(rng);
  image.upload(std::as_bytes(std::span(texels)));
  EXPECT_EQ(image.download<float>(), texels);
}

TEST_F(ImageTest, ThreeDimensionalScalarRoundTrips) {
  gpu::Image volume(context(), {9, 10, 11, VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT, "volume"});
  std::vector<float> texels(9 * 10 * 11);
  std::iota(texels.begin(), texels.end(), 0.5f);
  volume.upload(std::as_bytes(std::span(texels)));
  EXPECT_EQ(volume.download<float>(), texels);
}

class SequenceTest : public GpuTest {};

TEST_F(SequenceTest, BarrierOrdersAFillBeforeTheReductionThatReadsIt) {
  const uint32_t n = 5000;
  gpu::Buffer values = gpu::Buffer::storage(context(), n * 4, "values");
  gpu::ReduceStats reduce(context(), pipelineCache(), n);
  gpu::Sequence sequence(context());
  sequence.fill(values, 0x3f800000u);  // 1.0f
  reduce.record(sequence, values, n);
  sequence.submit();
  EXPECT_EQ(reduce.result().sum, float(n));
  EXPECT_EQ(sequence.barrierCount(), 2u);  // fill → pass 1 → pass 2
}

TEST_F(SequenceTest, IndependentWorkGetsNoBarrier) {
  gpu::Buffer a = gpu::Buffer::storage(context(), 256, "a");
  gpu::Buffer b = gpu::Buffer::storage(context(), 256, "b");
  gpu::Sequence sequence(context());
  sequence.fill(a, 0);
  sequence.fill(b, 0);
  EXPECT_EQ(sequence.barrierCount(), 0u);
  sequence.copy(a, b);  // reads what the first fill wrote, writes what the second did
  EXPECT_EQ(sequence.barrierCount(), 1u);
  sequence.submit();
}

TEST_F(SequenceTest, ARecordedSequenceReplaysOnNewData) {
  const uint32_t n = 3000;
  gpu::Buffer values = gpu::Buffer::storage(context(), n * 4, "values");
  gpu::ReduceStats reduce(context(), pipelineCache(), n);
  gpu::Sequence sequence(context());
  reduce.record(sequence, values, n);
  sequence.finish();
  for (float v : {1.0f, 2.0f, -0.5f}) {
    values.upload(std::vector<float>(n, v));
    sequence.submit();
    EXPECT_EQ(reduce.result().sum, v * n);
  }
}

TEST_F(SequenceTest, TimestampsNameAndTimeEachStage) {
  const uint32_t n = 1 << 20;
  gpu::Buffer values = gpu::Buffer::storage(context(), n * 4, "values");
  gpu::ReduceStats reduce(context(), pipelineCache(), n);
  gpu::Sequence sequence(context());
  sequence.beginStage("clear");
  sequence.fill(values, 0);
  sequence.endStage();
  sequence.beginStage("reduce");
  reduce.record(sequence, values, n);
  sequence.endStage();
  sequence.submit();
  ASSERT_EQ(sequence.stageTimes().size(), 2u);
  EXPECT_EQ(sequence.stageTimes()[0].name, "clear");
  EXPECT_EQ(sequence.stageTimes()[1].name, "reduce");
  for (const auto& stage : sequence.stageTimes()) {
    EXPECT_GT(stage.milliseconds, 0.0) << stage.name;
    EXPECT_LT(stage.milliseconds, 10000.0) << stage.name;
  }
}

TEST_F(SequenceTest, MisuseIsReported) {
  gpu::Sequence sequence(context());
  EXPECT_THROW(sequence.endStage(), gpu::GpuError);
  sequence.beginStage("a");
  EXPECT_THROW(sequence.beginStage("b"), gpu::GpuError);
  EXPECT_THROW(sequence.finish(), gpu::GpuError);
  sequence.endStage();
  sequence.finish();
  gpu::Buffer buffer = gpu::Buffer::storage(context(), 16, "b");
  EXPECT_THROW(sequence.fill(buffer, 0), gpu::GpuError);
}

}  // namespace
}  // namespace sixway::test

namespace sixway::test {
namespace {

TEST_F(BufferTest, NewBuffersAreZero) {
  // Reused memory must not leak an earlier buffer's contents into a new one.
  for (int round = 0; round < 2; ++round) {
    gpu::Buffer buffer = gpu::Buffer::storage(context(), 1 << 16, "fresh");
    const std::vector<uint32_t> words = buffer.download<uint32_t>();
    EXPECT_TRUE(std::all_of(words.begin(), words.end(), [](uint32_t w) { return w == 0; }))
        << "round " << round;
    buffer.upload(std::vector<uint32_t>(words.size(), 0xdeadbeefu));
  }
}

}  // namespace
}  // namespace sixway::test
