// gpu::Sequence::dispatchLinear: a 1D range longer than the device's workgroup limit along x (65535 groups
// of 64 on lavapipe: a 128×256×128 lattice needs 65536) is folded into y, and linearInvocationIndex()
// (shaders/common/linear_index.glsl) visits every index below the count exactly once.
#include <gtest/gtest.h>

#include <vector>

#include "gpu/buffer.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "support/gpu_fixture.h"

namespace sixway::test {
namespace {

class DispatchLinearTest : public GpuTest {};

TEST_F(DispatchLinearTest, VisitsEveryIndexOnceBeyondTheGroupLimit) {
  const uint64_t maxGroups = context().limits().maxComputeWorkGroupCount[0];
  // NVIDIA allows 2^31 - 1 groups along x: no buffer a shader can bind is long enough to need the wrap there.
  if ((maxGroups * 64 + 77) * sizeof(uint32_t) > context().limits().maxStorageBufferRange)
    GTEST_SKIP() << "the x limit of " << maxGroups << " groups is beyond any bindable buffer on this device";
  for (const uint64_t count : {uint64_t(1000), maxGroups * 64 + 77}) {
    gpu::Buffer slots = gpu::Buffer::storage(context(), count * sizeof(uint32_t), "slots");
    gpu::ComputePipelineDesc desc;
    desc.shader = "gpu/linear_index_probe.comp";
    desc.bindings = {gpu::BindingType::StorageBuffer};
    desc.pushConstantBytes = sizeof(uint32_t);
    const gpu::Pipeline pipeline(context(), pipelineCache(), desc);
    gpu::Sequence sequence(context());
    sequence.dispatchLinear(pipeline, {gpu::readsWrites(slots)}, uint32_t(count), count, 64);
    sequence.submit();
    const std::vector<uint32_t> values = slots.download<uint32_t>();
    uint64_t wrong = 0;
    for (uint64_t i = 0; i < count; ++i) wrong += values[i] != uint32_t(i + 1);
    EXPECT_EQ(wrong, 0u) << "of " << count << " slots";
  }
}

}  // namespace
}  // namespace sixway::test
