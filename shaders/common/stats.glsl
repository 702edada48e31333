// Summary statistics of a float array, combined pairwise in a tree (the sum's rounding error
// then grows as log N, not N). Shared by the reduction shaders; the host mirror is gpu::Stats.
#ifndef SIXWAY_STATS_GLSL
#define SIXWAY_STATS_GLSL

struct Stats {
  float sum;            // of the finite values
  float minimum;        // of the finite values
  float maximum;        // of the finite values
  float maxAbs;         // largest |value| among the finite values
  uint maxAbsIndex;     // where it is
  uint nonFinite;       // count of NaN and Inf values
  uint firstNonFinite;  // smallest index of a NaN or Inf (0xffffffff when none)
  uint count;           // values summarised
};

const uint kNoIndex = 0xffffffffu;

Stats statsEmpty() {
  return Stats(0.0, uintBitsToFloat(0x7f800000u), uintBitsToFloat(0xff800000u), -1.0, kNoIndex, 0u, kNoIndex, 0u);
}

Stats statsOf(float value, uint index) {
  if (isnan(value) || isinf(value)) return Stats(0.0, uintBitsToFloat(0x7f800000u), uintBitsToFloat(0xff800000u),
                                                 -1.0, kNoIndex, 1u, index, 1u);
  return Stats(value, value, value, abs(value), index, 0u, kNoIndex, 1u);
}

Stats statsCombine(Stats a, Stats b) {
  Stats r;
  r.sum = a.sum + b.sum;
  r.minimum = min(a.minimum, b.minimum);
  r.maximum = max(a.maximum, b.maximum);
  // Ties go to the smaller index, so the result does not depend on the reduction order.
  bool takeB = b.maxAbs > a.maxAbs || (b.maxAbs == a.maxAbs && b.maxAbsIndex < a.maxAbsIndex);
  r.maxAbs = takeB ? b.maxAbs : a.maxAbs;
  r.maxAbsIndex = takeB ? b.maxAbsIndex : a.maxAbsIndex;
  r.nonFinite = a.nonFinite + b.nonFinite;
  r.firstNonFinite = min(a.firstNonFinite, b.firstNonFinite);
  r.count = a.count + b.count;
  return r;
}

#endif
