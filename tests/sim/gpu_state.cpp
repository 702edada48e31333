#include "gpu_state.h"

#include <Imath/half.h>

#include <algorithm>

namespace sixway::test {

std::vector<d3q19::Populations> downloadPopulations(const sim::LbmSolver& lbm, int parity) {
  constexpr int kPerBuffer = 5;
  const size_t cells = lbm.cells();
  std::vector<d3q19::Populations> out(cells);
  const bool fp16 = lbm.storage() == io::PopulationStorage::Fp16;
  for (int b = 0; b < 4; ++b) {
    std::vector<float> words;
    if (fp16) {  // (f_i − w_i) · 2¹⁴ as 16-bit floats (lbm_lattice.glsl); decoded below
      for (uint16_t bits : lbm.lattice(parity, b).download<uint16_t>()) {
        Imath::half value;
        value.setBits(bits);
        words.push_back(float(value) / 16384.0f);
      }
    } else {
      words = lbm.lattice(parity, b).download<float>();
    }
    for (int i = b * kPerBuffer; i < std::min(d3q19::kQ, (b + 1) * kPerBuffer); ++i)
      for (size_t c = 0; c < cells; ++c)
        out[c][i] = words[(i % kPerBuffer) * cells + c] + (fp16 ? d3q19::weight(i) : 0.0);
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
