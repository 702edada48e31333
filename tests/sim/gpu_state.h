#pragma once
// Reading the simulation's GPU state back into the oracles' terms: populations (lbm_lattice.glsl
// layout: population i of cell c is word (i % 5) · cells + c of buffer i / 5) and cell flags
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
