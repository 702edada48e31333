// Counter-based random numbers: every (seed, pixel, sample) starts its own PCG stream, so a render
// is the same whatever the split of samples into passes (Jarzynski & Olano 2020, "Hash Functions
// for GPU Rendering": pcg hash and PCG-RXS-M-XS steps).
#ifndef SIXWAY_RANDOM_GLSL
#define SIXWAY_RANDOM_GLSL

uint pcgHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

uint rngSeed(uint seed, uint pixel, uint sampleIndex) {
  return pcgHash(seed ^ pcgHash(pixel ^ pcgHash(sampleIndex)));
}

// Uniform in [0, 1): the top 24 bits of the next PCG output.
float rngNext(inout uint state) {
  state = state * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return float(((word >> 22u) ^ word) >> 8u) * (1.0 / 16777216.0);
}

#endif
