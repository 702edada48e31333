// The renderer's lightmaps for an engine's own material in each packing (RendererOptions::packing): the
// same smoke as Unity's A and B, moved to where the preset's table puts each channel, bit for bit, and a
// "repack" stage timed.
#include <gtest/gtest.h>
#include <sixway/device.h>
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>

#include <algorithm>
#include <glm/gtc/packing.hpp>
#include <vector>

#include "gpu/image.h"
#include "render/lightmap_packing.h"
#include "runtime/engine_harness.h"
#include "runtime/internal.h"

namespace sixway::test {
namespace {

TEST(LightmapPacking, EachPresetHoldsUnitysChannelsWhereItsTableSays) {
  Device device({.validate = true});
  const gpu::Context& context = runtime::Access::context(device);
  SmokeSimulation unitySimulation(device, kScene);
  SmokeRenderer unity(device, unitySimulation, {.weights = kWeights});
  unity.setCamera(sceneCamera());
  for (int frame = 0; frame < 2; ++frame) unitySimulation.advance();
  unity.render();
  const io::Image eight = runtime::Access::frame(unity).lightmaps().download();

  const std::pair<LightmapPacking, const char*> presets[] = {{LightmapPacking::RltBbf, "rlt-bbf"},
                                                             {LightmapPacking::O3de, "o3de"}};
  for (const auto& [packing, name] : presets) {
    SmokeSimulation simulation(device, kScene);
    SmokeRenderer renderer(device, simulation, {.weights = kWeights, .packing = packing});
    renderer.setCamera(sceneCamera());
    for (int frame = 0; frame < 2; ++frame) simulation.advance();
    renderer.render();
    const LightmapTextures maps = renderer.lightmaps();
    const gpu::ImageDesc desc{maps.width, maps.height, 1, maps.format, VK_IMAGE_USAGE_SAMPLED_BIT, "packed"};
    const std::vector<uint16_t> texels[2] = {
        gpu::Image::borrowed(context, maps.a, maps.viewA, desc).download<uint16_t>(),
        gpu::Image::borrowed(context, maps.b, maps.viewB, desc).download<uint16_t>()};
    const render::ChannelPacking table = render::packingPreset(name);
    for (int channel = 0; channel < render::kSixWayChannels; ++channel) {
      const render::ChannelPacking::Slot slot = table.slots[size_t(channel)];
      for (size_t p = 0; p < size_t(maps.width) * maps.height; ++p)
        ASSERT_EQ(texels[slot.texture][p * 4 + size_t(slot.component)],
                  glm::packHalf1x16(eight.pixels[p * 8 + size_t(channel)]))
            << name << " channel " << channel << " pixel " << p;
    }
    const std::vector<StageTime> times = renderer.stageTimes();
    EXPECT_TRUE(
        std::any_of(times.begin(), times.end(), [](const StageTime& t) { return t.name == "repack"; }));
  }
  EXPECT_EQ(device.validationMessages(), 0u);
}

}  // namespace
}  // namespace sixway::test
