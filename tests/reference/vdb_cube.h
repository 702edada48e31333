#pragma once
// The real smoke the reference-rendering tools measure on: tests/data/vdb/densityAndHeat.vdb's density
// resampled onto a cube of cells³ cubic cells around the union of its grids' world boxes.
#include "io/dense_grid.h"

namespace sixway::test {

io::DenseGrid densityAndHeatCube(int cells);

}  // namespace sixway::test
