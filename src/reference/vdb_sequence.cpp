#include "reference/vdb_sequence.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "io/error.h"
#include "io/json_reader.h"
#include "io/vdb.h"

namespace sixway::reference {
namespace {

bool usable(const io::VdbGridInfo& grid) {
  return grid.valueType == "float" && !grid.empty;
}

// U of scene::VdbSource: file space to the scene's y-up space, and back.
glm::vec3 toScene(glm::vec3 p, scene::VdbUp up) {
  return up == scene::VdbUp::Z ? glm::vec3(p.x, p.z, -p.y) : p;
}
glm::vec3 toFile(glm::vec3 p, scene::VdbUp up) {
  return up == scene::VdbUp::Z ? glm::vec3(p.x, -p.z, p.y) : p;
}

std::vector<std::string> gridNames(const scene::VdbSource& source) {
  std::vector<std::string> names = {source.densityGrid};
  if (source.temperatureGrid) names.push_back(*source.temperatureGrid);
  return names;
}

// Cubic cells of size `cell` over [lo, hi]; the box grows at its max side to whole cells. Native cells (the
// files' own, which no count bounds) are refused beyond kMaxVdbVoxels a side, before any count is made an
// int.
render::VolumeGrid cubicLattice(glm::vec3 lo, glm::vec3 hi, float cell, bool native,
                                const std::string& file) {
  const glm::vec3 counts = glm::ceil((hi - lo) / cell - 1e-4f);
  const float longest = std::max({counts.x, counts.y, counts.z});
  if (native && !(longest <= float(scene::kMaxVdbVoxels)))
    throw io::InputError(file, "native voxels make " + io::show(longest) +
                                   " cells along the lattice's longest axis, more than " +
                                   std::to_string(scene::kMaxVdbVoxels) + "; give a cell count");
  return {glm::max(glm::ivec3(counts), glm::ivec3(1)), lo, cell};
}

float longestSide(glm::vec3 lo, glm::vec3 hi) {
  const glm::vec3 extent = hi - lo;
  return std::max({extent.x, extent.y, extent.z});
}

// A lattice of the file's space placed in the scene: the same cells, turned, scaled and moved.
render::VolumeGrid inScene(const render::VolumeGrid& file, const scene::VdbSource& source) {
  const render::Box box = file.bounds();
  const glm::vec3 a = toScene(box.min, source.up), b = toScene(box.max, source.up);
  return {glm::abs(glm::ivec3(toScene(glm::vec3(file.size), source.up))),
          source.translate + source.scale * glm::min(a, b), source.scale * file.cellSize};
}

// How far a grid's world box reaches from the scene's origin once scaled and moved (the up turn keeps it), in
// metres: inf when it does not fit a float.
double sceneReach(const io::VdbGridInfo& grid, const scene::VdbSource& source) {
  double reach = 0;
  for (const glm::vec3& corner : {grid.worldMin, grid.worldMax})
    for (int axis = 0; axis < 3; ++axis) {
      const double p = double(source.translate[axis]) + double(source.scale) * double(corner[axis]);
      reach = std::max(reach, std::isfinite(p) ? std::abs(p) : std::numeric_limits<double>::infinity());
    }
  return reach;
}

// A grid that would stretch the lattice beyond scene::kMaxSceneMetres (a float box whose diagonal overflows,
// light grids without a size) is refused, naming the file and what placed it there.
void requireWithinScene(const std::filesystem::path& file, const io::VdbGridInfo& grid,
                        const scene::VdbSource& source) {
  const double reach = sceneReach(grid, source);
  if (reach <= scene::kMaxSceneMetres) return;
  throw io::InputError(file.string(),
                       "grid '" + grid.name + "' reaches " + io::show(float(reach)) +
                           " m from the origin (voxel size " + io::show(grid.voxelSize.x) + " × vdb.scale " +
                           io::show(source.scale) + "), more than " + io::show(scene::kMaxSceneMetres) +
                           " m; check the file's voxel size and vdb.scale, or give vdb.box_min/box_max");
}

// For "voxels": "native": the size of every grid's voxels, which must be cubic and the same in every file.
void requireOneVoxelSize(const std::filesystem::path& file, const io::VdbGridInfo& grid,
                         std::optional<float>& voxel) {
  const glm::vec3 size = grid.voxelSize;
  const auto same = [](float a, float b) { return std::abs(a - b) <= 1e-5f * std::max(a, b); };
  if (!same(size.x, size.y) || !same(size.y, size.z))
    throw io::InputError(file.string(), "grid '" + grid.name + "' has non-cubic voxels (" + io::show(size) +
                                            "): native voxels need cubic ones; give a cell count");
  if (voxel && !same(*voxel, size.x))
    throw io::InputError(file.string(), "grid '" + grid.name + "' has voxels of " + io::show(size.x) +
                                            ", other grids of " + io::show(*voxel) +
                                            ": native voxels need one size; give a cell count");
  voxel = size.x;
}

// The playback lattice: over the scene's box when it gives one, else over the union of the world boxes of
// the grids read (sized in the file's own space, so that turning a file moves its cells exactly) and one
// empty cell beyond it on every side, so that the smoke fades to zero over the cell beyond the last active
// voxel centre as OpenVDB's trilinear sampler (and Blender's Cycles) read a grid's inactive background.
render::VolumeGrid playbackLattice(const scene::VdbSource& source, std::vector<std::string>& notes) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  bool anyTemperature = false;
  const bool native = source.voxels == scene::kNativeVoxels;
  std::optional<float> voxel;
  for (const auto& file : source.files) {
    const std::vector<io::VdbGridInfo> grids = io::readVdbInfo(file).grids;
    // A file without the density grid would play as an empty frame: more likely a wrong file or grid name
    // than smoke that vanished (an empty grid, no active voxels, is a legitimate empty frame).
    if (std::ranges::none_of(grids, [&](const io::VdbGridInfo& g) {
          return g.name == source.densityGrid && g.valueType == "float";
        }))
      throw io::InputError(file.string(),
                           "has no float grid '" + source.densityGrid +
                               "' (set vdb.density_grid, or bake's --density-grid, to the density's name)");
    for (const io::VdbGridInfo& grid : grids) {
      const bool density = grid.name == source.densityGrid;
      const bool temperature = source.temperatureGrid && grid.name == *source.temperatureGrid;
      if (!(density || temperature) || !usable(grid)) continue;
      anyTemperature = anyTemperature || temperature;
      if (!source.box) requireWithinScene(file, grid, source);
      if (native) requireOneVoxelSize(file, grid, voxel);
      if (grid.voxelSize.x != grid.voxelSize.y || grid.voxelSize.y != grid.voxelSize.z) {
        const std::string note = file.filename().string() + ": grid '" + grid.name +
                                 "' has non-uniform voxels; resampled onto cubic cells";
        if (std::find(notes.begin(), notes.end(), note) == notes.end()) notes.push_back(note);
      }
      lo = glm::min(lo, grid.worldMin);
      hi = glm::max(hi, grid.worldMax);
    }
  }
  const std::string first = source.files.front().string();
  if (lo.x > hi.x)
    throw io::InputError(first,
                         "no file of the vdb sequence has a non-empty float grid '" + source.densityGrid +
                             "' (set vdb.density_grid, or bake's --density-grid, to the density's name)");
  if (source.temperatureGrid && !anyTemperature)
    throw io::InputError(first, "no file of the vdb sequence has a non-empty float grid '" +
                                    *source.temperatureGrid + "' (vdb.temperature_grid)");
  if (source.box) {
    if (native) throw io::InputError(first, "native voxels play the files' own cells: they take no box");
    const auto [boxMin, boxMax] = *source.box;
    return cubicLattice(boxMin, boxMax, longestSide(boxMin, boxMax) / float(source.voxels), false, first);
  }
  const float cell = native ? *voxel : longestSide(lo, hi) / float(source.voxels);
  return inScene(cubicLattice(lo - cell, hi + cell, cell, native, first), source);
}

// The grid read on the file's own axes, turned onto the scene's: scene cell (i, j, k) is file cell
// (i, n_y − 1 − k, j) when z is up.
std::vector<float> toSceneAxes(const io::DenseGrid& grid, scene::VdbUp up, glm::ivec3 cells) {
  if (up == scene::VdbUp::Y) return grid.values;
  std::vector<float> out(grid.values.size());
  std::size_t at = 0;
  for (int k = 0; k < cells.z; ++k)
    for (int j = 0; j < cells.y; ++j)
      for (int i = 0; i < cells.x; ++i) out[at++] = grid.at(i, grid.size.y - 1 - k, j);
  return out;
}

std::optional<std::string> temperatureGridIn(const std::vector<std::filesystem::path>& files) {
  for (const char* name : {"temperature", "heat"})
    for (const auto& file : files)
      for (const io::VdbGridInfo& grid : io::readVdbInfo(file).grids)
        if (grid.name == name && usable(grid)) return name;
  return std::nullopt;
}

scene::VdbSource fileList(std::vector<std::filesystem::path> files, int longestAxisCells,
                          bool withTemperature, std::string densityGrid) {
  scene::VdbSource source;
  source.densityGrid = std::move(densityGrid);
  source.temperatureGrid = withTemperature ? temperatureGridIn(files) : std::nullopt;
  source.files = std::move(files);
  source.voxels = longestAxisCells;
  return source;
}

}  // namespace

VdbSequence::VdbSequence(const gpu::Context& context, scene::VdbSource source)
    : source_(std::move(source)),
      lattice_(playbackLattice(source_, notes_)),
      volume_(context, lattice_, source_.temperatureGrid.has_value()) {}

VdbSequence::VdbSequence(const gpu::Context& context, std::vector<std::filesystem::path> files,
                         int longestAxisCells, bool withTemperature, std::string densityGrid)
    : VdbSequence(context,
                  fileList(std::move(files), longestAxisCells, withTemperature, std::move(densityGrid))) {}

io::VdbDenseGrids VdbSequence::read(int fileIndex, const std::vector<std::string>& names) {
  // The lattice back in the file's space: the same box, its axes turned back.
  const render::Box box = lattice_.bounds();
  const glm::vec3 a = toFile((box.min - source_.translate) / source_.scale, source_.up);
  const glm::vec3 b = toFile((box.max - source_.translate) / source_.scale, source_.up);
  const glm::ivec3 fileCells = glm::abs(glm::ivec3(toFile(glm::vec3(lattice_.size), source_.up)));
  const std::filesystem::path& path = source_.files[fileIndex];
  io::VdbDenseGrids grids =
      io::readVdbGrids(path, names, io::ExplicitBounds{glm::min(a, b), glm::max(a, b), fileCells});
  // Each note once: a looping playback (the demo) reads the same files again and again.
  for (const std::string& note : grids.notes)
    if (std::find(notes_.begin(), notes_.end(), note) == notes_.end()) notes_.push_back(note);
  return grids;
}

float VdbSequence::densityBound(int first, int count) {
  float largest = 0;
  const int lastFile = std::min((first + count - 1) / source_.framesPerFile, int(source_.files.size()) - 1);
  for (int file = std::max(first, 0) / source_.framesPerFile; file <= lastFile; ++file) {
    const io::VdbDenseGrids grids = read(file, {source_.densityGrid});
    const auto density = grids.grids.find(source_.densityGrid);
    if (density != grids.grids.end())
      for (float value : density->second.values) largest = std::max(largest, value);
  }
  return largest * source_.densityScale;
}

bool VdbSequence::load(int frame) {
  const int fileIndex = frame / source_.framesPerFile;
  if (fileIndex == loadedFile_) return !loadedEmpty_;
  const io::VdbDenseGrids read = this->read(fileIndex, gridNames(source_));
  loadedFile_ = fileIndex;
  const auto density = read.grids.find(source_.densityGrid);
  loadedEmpty_ = density == read.grids.end();
  const std::size_t cells = std::size_t(lattice_.size.x) * lattice_.size.y * lattice_.size.z;
  std::vector<float> rho = loadedEmpty_ ? std::vector<float>(cells, 0.0f)
                                        : toSceneAxes(density->second, source_.up, lattice_.size);
  for (float& value : rho) value *= source_.densityScale;
  std::vector<float> temperature;
  if (source_.temperatureGrid) {
    const auto found = read.grids.find(*source_.temperatureGrid);
    temperature = found == read.grids.end() || loadedEmpty_
                      ? std::vector<float>(cells, 0.0f)
                      : toSceneAxes(found->second, source_.up, lattice_.size);
  }
  volume_.upload(rho, temperature);
  return !loadedEmpty_;
}

std::optional<render::Volume> VdbSequence::frame(int index) {
  if (!load(index)) return std::nullopt;
  return volume_.view();
}

render::Volume VdbSequence::volume(int index) {
  load(index);
  return volume_.view();
}

}  // namespace sixway::reference
