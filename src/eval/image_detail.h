#pragma once
// The fine detail of a frame (docs/conventions.md, "Metrics"): the energy of its luminance above a Gaussian
// blur of σ = 2 pixels, Σ (Y − G_σ ∗ Y)² over the pixels of a mask, Y the Rec. 709 luminance of linear R, G,
// B clipped to [0, 1] as the PSNR clips them. A method's detail is its energy over the truth's; the truth's
// own Monte Carlo noise adds energy at these frequencies, which two renders a and b with independent noise
// take out: E(signal) = E(a) − E(a − b) / 2 (each render's noise carries E(a − b) / 2 in expectation).
#include <cstdint>
#include <vector>

#include "io/image.h"

namespace sixway::eval {

inline constexpr float kDetailSigma = 2.0f;  // pixels

// The high-pass energy of an RGBA image where `mask` (one byte per pixel) is set.
double highPassEnergy(const io::Image& rgba, const std::vector<uint8_t>& mask);
// The same of the difference a − b of two RGBA images of one size.
double highPassEnergyOfDifference(const io::Image& a, const io::Image& b, const std::vector<uint8_t>& mask);

// Where the truth's alpha > 0.01: the mask of the masked PSNR.
std::vector<uint8_t> smokeMask(const io::Image& truth);

}  // namespace sixway::eval
