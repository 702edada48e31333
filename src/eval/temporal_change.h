#pragma once
// Temporal stability of final images (docs/conventions.md, "Metrics"; the target is a temporal difference
// within 20% of the reference's): the change between consecutive frames of one camera, over the pixels where
// the ground truth's alpha > 0.01 in either frame, on linear R, G, B clipped to [0, 1] as the PSNR is.
//
// A path-traced truth's change holds its Monte Carlo noise too: with independent seeds per frame,
// E[(a_i − a_{i−1})²] = (true change)² + 2σ². Rendering the same frame again with another seed measures
// E[(a − a')²] = 2σ² over the same pixels, so the truth's own RMS change is sqrt(raw² − noise²)
// (rmsCorrected). The mean absolute change has no such correction; it is reported raw.
#include <cstdint>
#include <nlohmann/json.hpp>

#include "io/image.h"

namespace sixway::eval {

struct TemporalChange {
  double absolute = 0, squared = 0;  // sums over the R, G, B values compared
  uint64_t values = 0;

  // `current` against `previous` (RGBA, one size) over the pixels where `truthPrevious` or `truthCurrent`
  // (the ground truth of those frames) has alpha > 0.01. Throws std::invalid_argument on other shapes.
  void add(const io::Image& previous, const io::Image& current, const io::Image& truthPrevious,
           const io::Image& truthCurrent);
  double meanAbsolute() const;  // NaN with nothing compared
  double rms() const;
};

// sqrt(max(0, raw.rms² − noise.rms²)): the truth's change with its noise taken out (NaN when either is).
double rmsWithoutNoise(const TemporalChange& raw, const TemporalChange& noise);

// {mean_abs, rms} (null where there is nothing to measure).
nlohmann::json temporalJson(const TemporalChange& change);

}  // namespace sixway::eval
