// Limits: the scene format's list limits match the arrays that take them, and a resource the device cannot
// hold becomes a one-line error that names the user's file and the setting to reduce.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "app/device_limits.h"
#include "gpu/buffer.h"
#include "render/gpu_layout.h"
#include "scene/scene.h"
#include "sim/sim_params.h"
#include "support/gpu_fixture.h"
#include "support/input_error.h"

namespace sixway::test {
namespace {

using ::testing::HasSubstr, ::testing::Not;

static_assert(scene::kMaxSceneInlets == sim::kMaxInlets);
static_assert(scene::kMaxSceneObstacles == sim::kMaxObstacles);
static_assert(scene::kMaxSceneLights == std::size_t(render::layout::kMaxLights));
static_assert(scene::kMaxRampKeys == std::size_t(render::layout::kMaxRampKeys));

class DeviceLimitsTest : public GpuTest {};

TEST_F(DeviceLimitsTest, ABufferBeyondTheDeviceNamesTheFileAndTheSettingToReduce) {
  const uint64_t tooBig = uint64_t(context().limits().maxStorageBufferRange) + 4;
  scene::Grid grid;
  grid.size = {512, 512, 512};
  const std::string message = inputErrorMessage([&] {
    app::withinDeviceLimits("scenes/big.json", app::gridSetting(grid),
                            [&] { return gpu::Buffer::storage(context(), tooBig, "cell flags"); });
  });
  EXPECT_THAT(message, namesFileAndProblem("scenes/big.json", "cell flags needs a storage buffer of"));
  EXPECT_THAT(message, HasSubstr("; reduce grid.size (512×512×512)"));
  EXPECT_THAT(message, Not(HasSubstr("reduce its size")));
}

TEST_F(DeviceLimitsTest, WhatFitsIsBuiltAndReturned) {
  const gpu::Buffer buffer = app::withinDeviceLimits(
      "x.json", "grid.size", [&] { return gpu::Buffer::storage(context(), 64, "small"); });
  EXPECT_EQ(buffer.size(), 64u);
}

}  // namespace
}  // namespace sixway::test
