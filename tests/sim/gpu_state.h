#pragma once
// Reading the simulation's GPU state back into the oracles' terms: populations (the post-collision
// populations f*_j of every cell, as the step of `parity` finds them: lbm_lattice.glsl's layout, slot i of
// stored cell c is word (i % 5) · stored cells + c of buffer i / 5; lbm_in_place.glsl's slots) and cell flags
// (sim_grid.glsl: bits 0..7 obstacle + 1, bits 8..15 the obstacle of the step before + 1, bits 16..23
// inlet + 1).
#include <cstdint>
#include <vector>

#include "cpu_d3q19.h"
#include "cpu_lbm.h"
#include "sim/lbm_solver.h"

namespace sixway::test {

std::vector<d3q19::Populations> downloadPopulations(const sim::LbmSolver& lbm, int parity);

uint32_t encodeFlags(const CellFlags& flags);
std::vector<uint32_t> encodeFlags(const std::vector<CellFlags>& flags);

}  // namespace sixway::test
