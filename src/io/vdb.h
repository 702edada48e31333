#pragma once
// OpenVDB volumes in and out. Reading resamples float grids onto a dense lattice through each grid's world
// transform (translation and non-uniform voxel sizes honoured, trilinear); writing stores dense grids as
// float fog volumes.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "io/dense_grid.h"

namespace sixway::io {

struct VdbGridInfo {
  std::string name;
  std::string valueType;  // as OpenVDB names it: "float", "int32", "vec3s", ...
  std::string gridClass;  // "fog volume", "level set", "staggered" or "unknown"
  glm::vec3 voxelSize{0.0f};
  int64_t activeVoxelCount = 0;
  bool empty = true;                         // no active voxels; the bounds below are then zero
  glm::ivec3 indexMin{0}, indexMax{0};       // active voxels in index space, inclusive
  glm::vec3 worldMin{0.0f}, worldMax{0.0f};  // world box covered by the active voxels (their extents)
};

struct VdbFile {
  std::filesystem::path path;
  std::vector<VdbGridInfo> grids;  // in file order
};

// Lists the grids of a VDB file. Throws InputError naming the file when it is missing, not a VDB file,
// truncated or corrupt.
VdbFile readVdbInfo(const std::filesystem::path& path);

// The world box covered by the active voxels of the grid(s) read, with cubic cells and `longestAxisCells`
// cells along its longest axis (the box is extended at its max side to a whole number of cells).
struct AutoBounds {
  int longestAxisCells = 128;
};
// A given world box split into `cells` cells (which need not be cubic).
struct ExplicitBounds {
  glm::vec3 worldMin{0.0f}, worldMax{0.0f};
  glm::ivec3 cells{0};
};
// An invalid request (no cells, an empty box) is a caller error: std::invalid_argument.
using DenseRequest = std::variant<AutoBounds, ExplicitBounds>;

// One float grid resampled onto the lattice of `request`. Throws InputError naming the file for a missing
// grid, a grid that is not float, or AutoBounds on an empty grid.
DenseGrid readVdbDense(const std::filesystem::path& path, std::string_view gridName,
                       const DenseRequest& request);

struct VdbDenseGrids {
  std::map<std::string, DenseGrid> grids;  // all on the same lattice
  std::vector<std::string> notes;          // "<file>: grid 'obstacles' is int32, not float: skipped"
};

// The non-empty float grids among `names` (every grid in the file when `names` is empty) on one common
// lattice; AutoBounds covers all of them. Missing, empty and non-float grids are skipped with a note, so a
// file with nothing usable gives no grids and notes. Throws InputError only for a file that cannot be read.
VdbDenseGrids readVdbGrids(const std::filesystem::path& path, const std::vector<std::string>& names,
                           const DenseRequest& request);

// Writes each dense grid as a float fog volume named by its key, with a transform that puts voxel (i, j, k)
// at the cell centre origin + (i + 0.5) * dx. Values with magnitude up to 1e-6 become inactive background
// (0). Throws InputError naming the file for cells that are not cubic, inconsistent grids, repeated or
// empty names, or a failed write.
void writeVdb(const std::filesystem::path& path,
              const std::vector<std::pair<std::string, const DenseGrid*>>& grids);

}  // namespace sixway::io
