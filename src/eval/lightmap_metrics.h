#pragma once
// Lightmap quality as docs/conventions.md, "Metrics" defines it: PSNR = 10·log10(1 / MSE) on linear values
// clipped to [0, 1], over all eight channels; the headline figure masked to the pixels where the reference
// alpha > 0.01, the full-frame figure next to it. Also per channel pair (the four adapters' outputs), masked.
#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>

namespace sixway::eval {

class LightmapMetrics {
 public:
  // One prediction against its reference: eight channels each in sixWayChannelNames() order,
  // pixel-interleaved, of the same size.
  void add(std::span<const float> predicted, std::span<const float> reference);

  uint64_t samples() const { return samples_; }
  // PSNR of the pooled squared errors (every pixel of every sample weighs the same), and the mean of the
  // samples' own masked PSNRs; masked PSNR per channel pair and per channel (null where exact, e.g. the
  // emission of smoke that has none).
  nlohmann::json summary() const;

 private:
  struct Sum {
    double squared = 0;
    uint64_t values = 0;
    double psnr() const;
  };
  Sum masked_, full_;
  std::array<Sum, 4> pairs_;     // right/left, top/bottom, back/front, alpha/emissive
  std::array<Sum, 8> channels_;  // sixWayChannelNames() order
  double samplePsnrSum_ = 0;
  uint64_t samples_ = 0, maskedSamples_ = 0;  // all, and those with any masked pixel
};

}  // namespace sixway::eval
