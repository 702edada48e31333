// The lattice's populations in place: one set of 19 per cell, read and written by the same step (the AA
// pattern of Bailey, Myre, Walsh, Lilja & Cracknell 2009, "Accelerating lattice Boltzmann fluid flow
// simulations using graphics processors"). Steps of two parities alternate; before a step of parity k,
// f*_j(y) — the population cell y sent along C[j] after its last collision — is kept in
//   k = 0: slot opposite(j) of cell y (its own cell),
//   k = 1: slot j of cell y + C[j] (the cell it streams to).
// So a step of parity 0 pulls its incoming populations from its neighbours and pushes its outgoing ones into
// them (leaving the state of parity 1), and a step of parity 1 reads and writes its own cell only (leaving the
// state of parity 0). Either way every slot a cell reads is one it writes and no other cell touches it: there
// is no second lattice to write into.
//
// A wall's populations come back by the boundary rules, which read kept populations other than the cell's
// incoming ones: its own population sent towards the wall (half-way bounce-back) and a tangential neighbour's
// sent out of the domain (free slip) lie in slots that belong in this step to the wall cell or to a cell outside
// the domain, which no invocation updates; the next fluid cell's sent towards this one (interpolated, q < ½) is
// this cell's own incoming slot, read before this cell writes it. So none races. Populations that leave the
// domain in a step of parity 0 need such a slot: the cells are stored with a ghost layer one cell deep across
// every face that is not periodic (STORED). Two cases cannot be read in place: a cell's own population sent away
// from the wall (interpolated, q > ½), which the next cell overwrites, is copied before the step
// (lbm_keep_away.comp); and a cell a moving obstacle uncovers this step, which would overwrite what its
// neighbours sent to the wall there, is updated after them (lbm_step.comp's UNCOVERED_CELLS).
//
// The including shader declares SIZE (ivec3), the faces' specialization constants (sim_faces.glsl), PARITY
// (uint) and, before including this file, the lattice as buffers a0..a3 of LbmPopulation (lbm_lattice.glsl),
// and includes lbm_d3q19.glsl and sim_grid.glsl first.
#ifndef SIXWAY_LBM_IN_PLACE_GLSL
#define SIXWAY_LBM_IN_PLACE_GLSL

#include "sim_faces.glsl"

// Ghost cells per side along each axis: none across periodic faces (both faces of an axis are periodic or
// neither, io::Scene).
const ivec3 PAD = ivec3(FACE_XM == FACE_PERIODIC ? 0 : 1, FACE_YM == FACE_PERIODIC ? 0 : 1,
                        FACE_ZM == FACE_PERIODIC ? 0 : 1);
const ivec3 STORED = SIZE + 2 * PAD;
const uint STORED_CELLS = uint(STORED.x * STORED.y * STORED.z);

#include "lbm_lattice.glsl"

// A cell moved back into the lattice across periodic faces (one lattice length at most).
ivec3 wrapPeriodic(ivec3 p) {
  [[unroll]] for (int a = 0; a < 3; ++a)
    if (faceType(2 * a) == FACE_PERIODIC) p[a] = (p[a] + SIZE[a]) % SIZE[a];
  return p;
}

// The storage index of cell p: a lattice cell, or a ghost cell one step outside a non-periodic face.
uint storedCell(ivec3 p) {
  p += PAD;
  return uint(p.x + STORED.x * (p.y + STORED.y * p.z));
}

// Where f*_j(y) is kept before a step of parity `parity`.
struct Slot {
  int population;
  uint cell;
};
Slot keptSlot(int j, ivec3 y, uint parity) {
  return parity == 0u ? Slot(opposite(j), storedCell(y)) : Slot(j, storedCell(wrapPeriodic(y + C[j])));
}

// f*_j(y) as this step (PARITY) finds it.
float loadKept(int j, ivec3 y) {
  Slot s = keptSlot(j, y, PARITY);
  return SIXWAY_LOAD(s.population, s.cell, a0, a1, a2, a3);
}

#endif
