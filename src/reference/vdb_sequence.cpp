#include "reference/vdb_sequence.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "io/error.h"
#include "io/vdb.h"

namespace sixway::render {
namespace {

const std::vector<std::string> kDensity = {"density"};
const std::vector<std::string> kTemperatureNames = {"temperature", "heat"};

bool usable(const io::VdbGridInfo& grid) {
  return grid.valueType == "float" && !grid.empty;
}

// The lattice of cubic cells over the union of the world boxes of the grids the sequence reads.
VolumeGrid unionLattice(const std::vector<std::filesystem::path>& files, int longestAxisCells,
                        bool withTemperature) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (const auto& file : files) {
    for (const io::VdbGridInfo& grid : io::readVdbInfo(file).grids) {
      const bool wanted = grid.name == "density" ||
                          (withTemperature && std::find(kTemperatureNames.begin(), kTemperatureNames.end(),
                                                        grid.name) != kTemperatureNames.end());
      if (!wanted || !usable(grid)) continue;
      lo = glm::min(lo, grid.worldMin);
      hi = glm::max(hi, grid.worldMax);
    }
  }
  if (lo.x > hi.x) return {glm::ivec3(1), glm::vec3(0.0f), 1.0f};  // nothing anywhere: every frame is empty
  const glm::vec3 extent = hi - lo;
  const float cell = std::max({extent.x, extent.y, extent.z}) / float(longestAxisCells);
  const glm::ivec3 cells = glm::max(glm::ivec3(glm::ceil(extent / cell - 1e-4f)), glm::ivec3(1));
  return {cells, lo, cell};
}

}  // namespace

VdbSequence::VdbSequence(const gpu::Context& context, std::vector<std::filesystem::path> files,
                         int longestAxisCells, bool withTemperature)
    : files_(std::move(files)),
      withTemperature_(withTemperature),
      lattice_(unionLattice(files_, longestAxisCells, withTemperature)),
      volume_(context, lattice_, withTemperature) {}

std::optional<Volume> VdbSequence::frame(int index) {
  std::vector<std::string> names = kDensity;
  if (withTemperature_) names.insert(names.end(), kTemperatureNames.begin(), kTemperatureNames.end());
  const Box box = lattice_.bounds();
  io::VdbDenseGrids read =
      io::readVdbGrids(files_[index], names, io::ExplicitBounds{box.min, box.max, lattice_.size});
  // A missing temperature or heat grid is expected (a file has one or the other, or neither); the rest is
  // news.
  for (const std::string& note : read.notes)
    if (note.find("no grid '") == std::string::npos || note.find("no grid 'density'") != std::string::npos)
      notes_.push_back(note);
  const auto density = read.grids.find("density");
  if (density == read.grids.end()) return std::nullopt;
  const io::DenseGrid* temperature = nullptr;
  for (const std::string& name : kTemperatureNames)
    if (!temperature && read.grids.count(name)) temperature = &read.grids.at(name);
  volume_.upload(density->second.values,
                 temperature ? std::span<const float>(temperature->values) : std::span<const float>());
  return volume_.view();
}

}  // namespace sixway::render
