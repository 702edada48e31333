// shaders/render/repack_lightmaps.comp (render::LightmapRepack) against the packing table itself
// (render::packingPreset, docs/formats.md "Packing presets"): every preset's two textures hold, component by
// component, the channel the table puts there, bit for bit (the pass copies half floats).
#include <gtest/gtest.h>

#include <glm/gtc/packing.hpp>
#include <random>

#include "gpu/sequence.h"
#include "render/lightmap_images.h"
#include "render/lightmap_repack.h"
#include "render/sixway.h"
#include "support/gpu_fixture.h"

namespace sixway::test {
namespace {

class LightmapRepackTest : public GpuTest {};

TEST_F(LightmapRepackTest, EveryPresetHoldsTheChannelsItsTableSays) {
  constexpr uint32_t kSize = 20;  // not a multiple of the workgroup's 8
  const auto& names = render::sixWayChannelNames();
  io::Image eight{static_cast<int>(kSize), static_cast<int>(kSize), {names.begin(), names.end()}};
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> value(0.0f, 2.0f);
  for (float& v : eight.pixels) v = value(rng);
  render::LightmapImages unity(context(), kSize, kSize);
  unity.upload(eight);
  for (const std::string& preset : render::packingPresetNames()) {
    const render::ChannelPacking packing = render::packingPreset(preset);
    render::LightmapRepack repack(context(), pipelineCache(), kSize, packing);
    gpu::Sequence sequence(context());
    repack.record(sequence, unity);
    sequence.submit();
    std::vector<uint16_t> texels[2] = {repack.texture(0).download<uint16_t>(),
                                       repack.texture(1).download<uint16_t>()};
    std::vector<int> seen(render::kSixWayChannels, 0);
    for (int t = 0; t < 2; ++t)
      for (int c = 0; c < 4; ++c) {
        int channel = -1;
        for (int k = 0; k < render::kSixWayChannels; ++k)
          if (packing.slots[size_t(k)].texture == t && packing.slots[size_t(k)].component == c) channel = k;
        for (size_t p = 0; p < size_t(kSize) * kSize; ++p) {
          const uint16_t expected =
              channel < 0 ? 0 : glm::packHalf1x16(eight.pixels[p * 8 + size_t(channel)]);
          ASSERT_EQ(texels[t][p * 4 + size_t(c)], expected)
              << preset << " " << packing.textures[size_t(t)] << "."
              << "RGBA"[c] << " pixel " << p;
        }
        if (channel >= 0) ++seen[size_t(channel)];
      }
    for (int k = 0; k < render::kSixWayChannels; ++k)
      EXPECT_EQ(seen[size_t(k)], 1) << preset << " " << names[k];
  }
}

}  // namespace
}  // namespace sixway::test
