#include "support/gpu_fixture.h"

#include <memory>
#include <string>

namespace sixway::test {

gpu::Context& GpuTest::context() {
  static std::unique_ptr<gpu::Context> context = [] {
    gpu::ContextOptions options;
    options.validate = true;
    return std::make_unique<gpu::Context>(options);
  }();
  return *context;
}

gpu::PipelineCache& GpuTest::pipelineCache() {
  static gpu::PipelineCache cache(context());  // in memory: tests never touch the user's cache
  return cache;
}

void GpuTest::SetUp() {
  messagesBefore_ = context().validationMessageCount();
}

void GpuTest::forgetValidationMessages() {
  context().validationLog()->clear();
  messagesBefore_ = 0;
}

void GpuTest::TearDown() {
  const uint32_t after = context().validationMessageCount();
  if (after != messagesBefore_) {
    std::string all;
    for (const std::string& m : context().validationLog()->messages()) all += "\n  " + m;
    ADD_FAILURE() << (after - messagesBefore_) << " Vulkan validation message(s) during the test:" << all;
  }
}

}  // namespace sixway::test
