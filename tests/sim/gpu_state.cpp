#include "gpu_state.h"

#include <algorithm>

namespace sixway::test {

std::vector<d3q19::Populations> downloadPopulations(const sim::LbmSolver& lbm, int parity) {
  constexpr int kPerBuffer = 5;
  const size_t cells = lbm.cells();
  std::vector<d3q19::Populations> out(cells);
  for (int b = 0; b < 4; ++b) {
    const std::vector<float> words = lbm.lattice(parity, b).download<float>();
    for (int i = b * kPerBuffer; i < std::min(d3q19::kQ, (b + 1) * kPerBuffer); ++i)
      for (size_t c = 0; c < cells; ++c) out[c][i] = words[(i % kPerBuffer) * cells + c];
  }
  return out;
}

uint32_t encodeFlags(const CellFlags& flags) {
  return uint32_t(flags.obstacle + 1) | (uint32_t(flags.previousObstacle + 1) << 8) |
         (uint32_t(flags.inlet + 1) << 16);
}

std::vector<uint32_t> encodeFlags(const std::vector<CellFlags>& flags) {
  std::vector<uint32_t> out;
  for (const CellFlags& f : flags) out.push_back(encodeFlags(f));
  return out;
}

}  // namespace sixway::test
