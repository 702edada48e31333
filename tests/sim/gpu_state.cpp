#include "gpu_state.h"

#include <Imath/half.h>

#include <algorithm>

namespace sixway::test {

std::vector<d3q19::Populations> downloadPopulations(const sim::LbmSolver& lbm, int parity) {
  constexpr int kPerBuffer = 5;
  const glm::ivec3 size = lbm.size(), stored = lbm.storedSize();
  const glm::ivec3 pad = (stored - size) / 2;  // ghost cells per side; 0 across periodic faces
  const size_t storedCells = size_t(stored.x) * stored.y * stored.z;
  const bool fp16 = lbm.storage() == scene::PopulationStorage::Fp16;
  std::vector<std::vector<double>> slots(d3q19::kQ);  // slot i of every stored cell, decoded
  for (int b = 0; b < 4; ++b) {
    std::vector<float> words;
    if (fp16) {  // (f_i − w_i) · 2¹⁴ as 16-bit floats (lbm_lattice.glsl); decoded below
      for (uint16_t bits : lbm.lattice(b).download<uint16_t>()) {
        Imath::half value;
        value.setBits(bits);
        words.push_back(float(value) / 16384.0f);
      }
    } else {
      words = lbm.lattice(b).download<float>();
    }
    for (int i = b * kPerBuffer; i < std::min(d3q19::kQ, (b + 1) * kPerBuffer); ++i)
      for (size_t c = 0; c < storedCells; ++c)
        slots[i].push_back(words[(i % kPerBuffer) * storedCells + c] + (fp16 ? d3q19::weight(i) : 0.0));
  }
  const auto storedIndex = [&](glm::ivec3 p) {
    for (int a = 0; a < 3; ++a)
      if (pad[a] == 0) p[a] = (p[a] + size[a]) % size[a];  // periodic
    p += pad;
    return size_t(p.x) + size_t(stored.x) * (size_t(p.y) + size_t(stored.y) * size_t(p.z));
  };
  // Where the step of parity `parity` finds f*_j(y) (lbm_in_place.glsl): slot opposite(j) of y for parity 0,
  // slot j of y + c_j (wrapped across periodic faces, else a ghost cell) for parity 1.
  std::vector<d3q19::Populations> out(lbm.cells());
  for (int z = 0; z < size.z; ++z)
    for (int y = 0; y < size.y; ++y)
      for (int x = 0; x < size.x; ++x) {
        const glm::ivec3 p(x, y, z);
        d3q19::Populations& f = out[size_t(x) + size_t(size.x) * (size_t(y) + size_t(size.y) * size_t(z))];
        for (int j = 0; j < d3q19::kQ; ++j)
          f[j] = parity == 0 ? slots[d3q19::opposite(j)][storedIndex(p)]
                             : slots[j][storedIndex(p + d3q19::velocity(j))];
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
