#include "vdb_cube.h"

#include <algorithm>
#include <string>

#include "io/vdb.h"

namespace sixway::test {

io::DenseGrid densityAndHeatCube(int cells) {
  const std::string file = SIXWAY_TEST_DATA_DIR "/vdb/densityAndHeat.vdb";
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const auto& g : io::readVdbInfo(file).grids) {
    lo = glm::min(lo, g.worldMin);
    hi = glm::max(hi, g.worldMax);
  }
  const float side = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  const glm::vec3 centre = 0.5f * (lo + hi);
  return io::readVdbDense(file, "density",
                          io::ExplicitBounds{centre - 0.5f * side, centre + 0.5f * side, glm::ivec3(cells)});
}

}  // namespace sixway::test
