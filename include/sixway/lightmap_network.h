#pragma once
// The network alone: a weights file (docs/network-format.md) run on a guiding map, on sixway's own device.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <vector>

namespace sixway {

class Device;

class LightmapNetwork {
 public:
  // For size × size guiding maps (a multiple of 16). Throws Error naming the file when it is missing or
  // malformed.
  LightmapNetwork(Device& device, const std::filesystem::path& weights, uint32_t size, bool fp16 = false);
  // The same from the file's bytes in memory (read during construction).
  LightmapNetwork(Device& device, std::span<const std::byte> weights, uint32_t size, bool fp16 = false);
  ~LightmapNetwork();
  LightmapNetwork(const LightmapNetwork&) = delete;
  LightmapNetwork& operator=(const LightmapNetwork&) = delete;

  uint32_t size() const;
  // 0: the guide's 4th channel is unused; > 0: the network reads there the fine alpha of this step (voxels;
  // the guiding map's render.guide_alpha_step_voxels), as it was trained.
  float fineAlphaStepVoxels() const;
  // Whether the network's guide has a 5th channel: the direct emission of the fine march (the guiding map's
  // emission image, docs/real-time-rendering.md).
  bool readsEmission() const;
  // Whether the network reads the smoke's single-scattering albedo (run's `albedo`): the multiply-scattered
  // light depends on it beyond what the guide shows (docs/network-format.md).
  bool readsAlbedo() const;
  // `guide`: size² RGBA pixels, row 0 at the top (guide light, alpha, shell depth, fine alpha or unused; the
  // guiding map of docs/real-time-rendering.md); `emission`: size² values when readsEmission(), else empty;
  // `albedo`: the smoke's (the one its guide was marched with; a scene's default 0.9), read when
  // readsAlbedo(). Returns size² pixels of eight channels: right, left, top, bottom, back, front, alpha,
  // emissive (docs/conventions.md). Waits for the GPU. Throws std::invalid_argument for inputs of another
  // size or an albedo outside [0, 1].
  std::vector<float> run(std::span<const float> guide, std::span<const float> emission = {},
                         float albedo = 0.9f);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sixway
