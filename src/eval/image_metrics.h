#pragma once
// Final-image quality as docs/conventions.md, "Metrics" defines it, for `sixway eval --scene`:
// PSNR = 10·log10(1 / MSE) on linear R, G, B clipped to [0, 1]; the headline figure masked to the pixels
// where the ground truth's alpha > 0.01 (the smoke, and the obstacles it draws), the full-frame figure next
// to it, and the band figure, masked to the band around the obstacles (obstacle_band.h) too. Alpha itself is
// not compared: the methods composite the smoke over the same backdrop, so its colour already carries the
// smoke's opacity.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "io/image.h"

namespace sixway::eval {

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

// 10·log10(1 / mse): +∞ for 0, NaN for NaN.
double psnrDb(double mse);

}  // namespace sixway::eval
