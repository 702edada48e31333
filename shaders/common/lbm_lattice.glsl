// Population storage: structure of arrays in 4 buffers per lattice (populations 0–4, 5–9, 10–14,
// 15–18), so no single buffer exceeds the storage-buffer range (128 MiB on lavapipe holds 5
// populations of 6.7 M cells in fp32, 13.4 M in fp16). Population i of cell c is element
// (i % 5) · CELLS + c of buffer i / 5.
// The including shader declares CELLS and the buffers F0..F3 (read) and, to write, G0..G3, with elements of
// type LbmPopulation, and includes lbm_d3q19.glsl first.
//
// With LBM_FP16 the elements are 16-bit floats holding the shifted and scaled population
// (f_i − w_i) · 2¹⁴: the shift removes the rest state, which a 16-bit float would otherwise spend its
// 11 significant bits on (f_i − w_i is O(10⁻³) at lattice Mach numbers), and the scale moves the deviations
// out of the subnormal range (down to 4·10⁻⁹) while |f_i − w_i| < 4 still fits (Lehmann et al. 2022,
// "Accuracy and performance of the lattice Boltzmann method with 64-bit, 32-bit, and customized 16-bit
// number formats"). Arithmetic stays 32-bit.
#ifndef SIXWAY_LBM_LATTICE_GLSL
#define SIXWAY_LBM_LATTICE_GLSL

const int POPULATIONS_PER_BUFFER = 5;

uint populationWord(int i, uint cell) { return uint(i % POPULATIONS_PER_BUFFER) * CELLS + cell; }

#ifdef LBM_FP16
#extension GL_EXT_shader_16bit_storage : require
// Macros, not functions: with 16-bit storage alone a 16-bit value may be loaded, stored and converted, but not
// passed to a function.
#define LbmPopulation float16_t
const float POPULATION_SCALE = 16384.0;
#define decodePopulation(i, stored) (float(stored) * (1.0 / POPULATION_SCALE) + W[i])
#define encodePopulation(i, f) float16_t(((f) - W[i]) * POPULATION_SCALE)
#else
#define LbmPopulation float
#define decodePopulation(i, stored) (stored)
#define encodePopulation(i, f) (f)
#endif

#define SIXWAY_LOAD(i, cell, A0, A1, A2, A3)                                                                  \
  decodePopulation(i, (i) < 5    ? A0[populationWord(i, cell)]                                              \
                      : (i) < 10 ? A1[populationWord(i, cell)]                                              \
                      : (i) < 15 ? A2[populationWord(i, cell)]                                              \
                                 : A3[populationWord(i, cell)])

#define SIXWAY_STORE(i, cell, value, A0, A1, A2, A3)          \
  {                                                           \
    uint word_ = populationWord(i, cell);                     \
    float value_ = (value);                                   \
    if ((i) < 5) A0[word_] = encodePopulation(i, value_);     \
    else if ((i) < 10) A1[word_] = encodePopulation(i, value_); \
    else if ((i) < 15) A2[word_] = encodePopulation(i, value_); \
    else A3[word_] = encodePopulation(i, value_);             \
  }

#endif
