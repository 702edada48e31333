// gpu::measureCopyBandwidth, the reference of the LBM's bandwidth figures: it verifies the shader copy word
// by word (throwing where a word is missed) and returns a finite, positive rate.
#include <gtest/gtest.h>

#include <cmath>

#include "gpu/bandwidth.h"
#include "support/gpu_fixture.h"

namespace sixway::test {
namespace {

class CopyBandwidthTest : public GpuTest {};

TEST_F(CopyBandwidthTest, CopiesExactlyAndReportsAPositiveRate) {
  const double gbPerSecond = gpu::measureCopyBandwidth(context());
  EXPECT_TRUE(std::isfinite(gbPerSecond));
  EXPECT_GT(gbPerSecond, 0.0);
}

}  // namespace
}  // namespace sixway::test
