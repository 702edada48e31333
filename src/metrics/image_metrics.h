#pragma once
// Final-image quality as docs/conventions.md, "Metrics" defines it (`sixway eval --scene`, the demo's split
// view): PSNR = 10·log10(1 / MSE) on linear R, G, B clipped to [0, 1]; the headline figure masked to the
// pixels where the ground truth's alpha > 0.01 (the smoke, and the obstacles it draws), the full-frame figure
// next to it, and the band figure, masked to the band around the obstacles (eval/obstacle_band.h) too. Alpha
// itself is not compared: the methods composite the smoke over the same backdrop, so its colour already
// carries the smoke's opacity.
#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/image.h"

namespace sixway::metrics {

struct ImageError {
  double squaredMasked = 0, squaredFull = 0, squaredBand = 0;  // sums over the R, G, B values
  uint64_t valuesMasked = 0, valuesFull = 0, valuesBand = 0;

  double mseMasked() const;
  double mseFull() const;
  double mseBand() const;
  ImageError& operator+=(const ImageError& other);
  // {mse_masked, psnr_masked_db, mse_full, psnr_full_db, mse_band, psnr_band_db}; null where there is nothing
  // to measure.
  nlohmann::json json() const;
};

// `predicted` against `truth`, both RGBA of the same size (throws std::invalid_argument otherwise); the band
// figure over the pixels of `band` (one byte per pixel) within the mask, none without a band.
ImageError compareImages(const io::Image& predicted, const io::Image& truth,
                         const std::vector<uint8_t>* band = nullptr);

// The fraction of `frame`'s pixels (RGBA) whose alpha is at least `threshold`: how much of the picture the
// smoke (and any opaque obstacle drawn in it) covers.
double alphaCoverage(const io::Image& frame, float threshold = 0.1f);

// Pixels that no renderer should make, in a linear RGBA frame: not finite (NaN, ±∞, in any channel), negative
// (any channel below −1e-6), and dark dots: a pixel whose luminance is under half that of every pixel of the
// ring four pixels around it (the 9 × 9 square's border), all at least 0.03 — a hole up to 7 × 7 pixels
// inside lit smoke or an obstacle; not the dark background, nor an edge, which reaches the ring.
struct ImageFaults {
  uint64_t notFinite = 0, negative = 0, darkDots = 0;
  std::vector<std::array<int, 2>> first;  // (x, y) of the first faulty pixels, row by row, at most 8
  uint64_t total() const { return notFinite + negative + darkDots; }
};
ImageFaults imageFaults(const io::Image& frame);
// "N non-finite, N negative and N pixels in dark dots (the first at x X, y Y)", for a frame with faults.
std::string describeFaults(const ImageFaults& faults);

// 10·log10(1 / mse): +∞ for 0, NaN for NaN.
double psnrDb(double mse);

}  // namespace sixway::metrics
