// Population storage: structure of arrays in 4 buffers per lattice (populations 0–4, 5–9, 10–14,
// 15–18), so no single buffer exceeds the storage-buffer range (128 MiB on lavapipe holds 5
// populations of 6.7 M cells). Population i of cell c is word (i % 5) · CELLS + c of buffer i / 5.
// The including shader declares CELLS and the buffers F0..F3 (read) and, to write, G0..G3.
#ifndef SIXWAY_LBM_LATTICE_GLSL
#define SIXWAY_LBM_LATTICE_GLSL

const int POPULATIONS_PER_BUFFER = 5;

uint populationWord(int i, uint cell) { return uint(i % POPULATIONS_PER_BUFFER) * CELLS + cell; }

#define SIXWAY_LOAD(i, cell, A0, A1, A2, A3)                                         \
  ((i) < 5 ? A0[populationWord(i, cell)] : (i) < 10 ? A1[populationWord(i, cell)] \
           : (i) < 15 ? A2[populationWord(i, cell)] : A3[populationWord(i, cell)])

#endif
