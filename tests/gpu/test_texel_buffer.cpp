// Buffers bound as storage texel buffers through a BufferView: read with imageLoad in one dispatch, written
// as a storage buffer in the next, with the barrier between them placed from the underlying buffer.
#include <gtest/gtest.h>

#include <vector>

#include "gpu/buffer.h"
#include "gpu/check.h"
#include "gpu/gpu_spec.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "support/gpu_fixture.h"

namespace sixway::test {
namespace {

class TexelBufferTest : public GpuTest {
 protected:
  static constexpr uint32_t kTexels = 100;
  gpu::Buffer texelBuffer(const char* name) {
    return gpu::Buffer(context(), kTexels * 16,
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT |
                           VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                       gpu::MemoryKind::Device, name);
  }
  gpu::Pipeline scalePipeline(float scale) {
    gpu::ComputePipelineDesc desc;
    desc.shader = "gpu/texel_buffer_scale.comp";
    desc.bindings = {gpu::BindingType::StorageTexelBuffer, gpu::BindingType::StorageBuffer};
    desc.pushConstantBytes = sizeof(uint32_t);
    desc.spec.set(gpu::spec::kScale, scale);
    return gpu::Pipeline(context(), pipelineCache(), desc);
  }
};

TEST_F(TexelBufferTest, ReadsTexelsWrittenAsAStorageBufferAfterABarrier) {
  std::vector<float> values(kTexels * 4);
  for (size_t i = 0; i < values.size(); ++i) values[i] = float(i) * 0.5f - 7.0f;
  gpu::Buffer first = texelBuffer("first"), second = texelBuffer("second"), third = texelBuffer("third");
  first.upload(values);
  const gpu::BufferView firstView(context(), first, VK_FORMAT_R32G32B32A32_SFLOAT);
  const gpu::BufferView secondView(context(), second, VK_FORMAT_R32G32B32A32_SFLOAT);
  gpu::Pipeline pipeline = scalePipeline(2.0f);

  gpu::Sequence sequence(context());
  sequence.dispatch(pipeline, {gpu::reads(firstView), gpu::writes(second)}, kTexels, 2);
  sequence.dispatch(pipeline, {gpu::reads(secondView), gpu::writes(third)}, kTexels,
                    2);  // reads what was written
  sequence.submit();
  EXPECT_EQ(sequence.barrierCount(), 1u);
  const std::vector<float> result = third.download<float>();
  for (size_t i = 0; i < values.size(); ++i) EXPECT_EQ(result[i], 4.0f * values[i]) << i;
}

TEST_F(TexelBufferTest, AViewKeepsItsBarriersWhenItsBufferMoves) {
  // A network feature map holds a buffer and a view of it, and maps move (into vectors). The view once
  // followed the Buffer object, so after a move the barrier was keyed to the moved-from object (found by
  // AddressSanitizer: stack-use-after-scope in tools/sanitize.sh) and the write→read barrier went missing.
  std::vector<float> values(kTexels * 4, 3.0f);
  gpu::Buffer first = texelBuffer("first"), third = texelBuffer("third");
  first.upload(values);
  const gpu::BufferView firstView(context(), first, VK_FORMAT_R32G32B32A32_SFLOAT);
  gpu::Buffer original = texelBuffer("second");
  const gpu::BufferView secondView(context(), original, VK_FORMAT_R32G32B32A32_SFLOAT);
  const gpu::Buffer second = std::move(original);
  gpu::Pipeline pipeline = scalePipeline(2.0f);

  gpu::Sequence sequence(context());
  sequence.dispatch(pipeline, {gpu::reads(firstView), gpu::writes(second)}, kTexels, 2);
  sequence.dispatch(pipeline, {gpu::reads(secondView), gpu::writes(third)}, kTexels, 2);
  sequence.submit();
  EXPECT_EQ(sequence.barrierCount(), 1u);
  const std::vector<float> result = third.download<float>();
  for (size_t i = 0; i < values.size(); ++i) EXPECT_EQ(result[i], 12.0f) << i;
}

TEST_F(TexelBufferTest, ABufferBoundWhereATexelViewIsExpectedIsRefused) {
  gpu::Buffer buffer = texelBuffer("plain");
  gpu::Pipeline pipeline = scalePipeline(1.0f);
  gpu::Sequence sequence(context());
  EXPECT_THROW(sequence.dispatch(pipeline, {gpu::reads(buffer), gpu::writes(buffer)}, kTexels, 2),
               gpu::GpuError);
}

}  // namespace
}  // namespace sixway::test
