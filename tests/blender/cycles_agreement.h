#pragma once
// sixway's renders against Cycles' renders of the same thing, compared as docs/conventions.md, "Metrics"
// defines it (linear values clipped to [0, 1], masked where the reference's alpha > 0.01), with the Monte
// Carlo noise of each side measured from two independent renders and taken out: for renders a, b of one
// renderer the mean (a + b) / 2 has a variance per value of E[(a − b)²] / 4, so
//   bias² = MSE(mean of one, mean of the other) − MSE(a₁, b₁) / 4 − MSE(a₂, b₂) / 4.
#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sixway::test {

// One render: named planar channels of width · height values, row 0 at the top, and the alpha that masks.
struct Render {
  int width = 0, height = 0;
  std::vector<std::vector<float>> channels;
  std::vector<float> alpha;
};

// Lightmaps: the six light channels, then emissive (channels 0..6); alpha apart.
// A frame of `sixway bake` (frames/frame_NNNN.exr).
Render readBakedFrame(const std::filesystem::path& exr);
// What tools/blender/cycles_lightmaps.py wrote into `dir`: cycles_<Channel>.exr (R: the light, A: alpha; the
// alpha is the mean over the six renders) and cycles_emissive.exr when present (else 0).
Render readCyclesLightmaps(const std::filesystem::path& dir);

// Final images: R, G, B over the scene's background.
// A frame of `sixway render --exr` (its alpha is not read: the reference's masks).
Render readRenderedFrame(const std::filesystem::path& exr);
// What tools/blender/cycles_scene.py wrote into `dir`: cycles.exr (premultiplied, alpha) put over the
// background that cycles.json names.
Render readCyclesImage(const std::filesystem::path& dir);

// Sums over the masked values of every channel compared (the renders clipped to [0, 1]).
struct Agreement {
  double squared = 0;           // (mean of one − mean of the other)²
  double noise = 0;             // the two means' noise variance, estimated from the renders
  double texelBiasSquares = 0;  // (a texel's Σ over its channels of difference² − noise)²
  double tested = 0, reference = 0;
  std::size_t values = 0, texels = 0;

  double psnrDb() const;        // of the mean squared difference
  double noiseFloorDb() const;  // of the noise: the PSNR that noise alone would give
  double biasPsnrDb() const;    // noise removed (+∞ when the difference is within the noise)
  // The same at the squared bias's estimate plus two standard errors: what the tolerances hold, so that noise
  // cannot pass for agreement.
  double biasPsnrLowerDb() const;
  nlohmann::json json() const;
};

// Channels `channels` of `tested` (one render, or two independent ones) against those of `reference` (two
// independent renders), pooled; the mask is the reference's mean alpha > 0.01. Throws std::invalid_argument
// for renders that differ in size or channels.
Agreement compareRenders(const std::vector<Render>& tested, const std::vector<Render>& reference,
                         const std::vector<int>& channels);
// The same for the alpha channels.
Agreement compareAlpha(const std::vector<Render>& tested, const std::vector<Render>& reference);
// The share of texels the mask holds.
double maskedFraction(const std::vector<Render>& reference);

}  // namespace sixway::test
