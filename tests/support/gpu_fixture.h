#pragma once
// GoogleTest fixture for GPU tests: one Vulkan context per test process with the validation
// layers on; a test fails if any validation message appears while it runs.
#include <gtest/gtest.h>

#include "gpu/context.h"
#include "gpu/pipeline.h"

namespace sixway::test {

class GpuTest : public ::testing::Test {
 protected:
  static gpu::Context& context();
  static gpu::PipelineCache& pipelineCache();

  void SetUp() override;
  void TearDown() override;
  // For tests that provoke validation messages on purpose.
  void forgetValidationMessages();

 private:
  uint32_t messagesBefore_ = 0;
};

}  // namespace sixway::test
