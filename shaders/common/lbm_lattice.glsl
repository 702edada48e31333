// Population storage: structure of arrays in 4 buffers per lattice (populations 0–4, 5–9, 10–14,
// 15–18), so no single buffer exceeds the storage-buffer range (128 MiB on lavapipe holds 5
// populations of 6.7 M cells in fp32, 13.4 M in fp16). Population slot i of stored cell c is element
// (i % 5) · STORED_CELLS + c of buffer i / 5 (lbm_in_place.glsl says which slot holds which population).
// The including shader declares the buffers, with elements of type LbmPopulation, and STORED_CELLS before
// the first load or store, and includes lbm_d3q19.glsl first.
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

// A macro, so that STORED_CELLS may be declared after this file (the buffers' element type is needed first).
#define populationWord(i, cell) (uint((i) % POPULATIONS_PER_BUFFER) * STORED_CELLS + (cell))

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

// The stored (encoded) value of population slot i at `word` of buffers A0..A3, and its store.
#define SIXWAY_RAW(i, word, A0, A1, A2, A3) \
  ((i) < 5 ? A0[word] : (i) < 10 ? A1[word] : (i) < 15 ? A2[word] : A3[word])
#define SIXWAY_STORE_RAW(i, word, raw, A0, A1, A2, A3) \
  {                                                    \
    if ((i) < 5) A0[word] = (raw);                     \
    else if ((i) < 10) A1[word] = (raw);               \
    else if ((i) < 15) A2[word] = (raw);               \
    else A3[word] = (raw);                             \
  }

#define SIXWAY_LOAD(i, cell, A0, A1, A2, A3) decodePopulation(i, SIXWAY_RAW(i, populationWord(i, cell), A0, A1, A2, A3))
#define SIXWAY_STORE(i, cell, value, A0, A1, A2, A3) \
  SIXWAY_STORE_RAW(i, populationWord(i, cell), encodePopulation(i, (value)), A0, A1, A2, A3)

#endif
