#include "io/vdb.h"

#include <openvdb/io/Archive.h>
#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include "io/error.h"
#include "io/file_access.h"
#include "io/json_reader.h"

namespace sixway::io {

namespace {

// io::File writes through a std::ofstream it never checks: on a full disk it leaves a truncated file and no
// error. This encodes the same archive (seekable, as io::File::write does) in memory, so that
// AtomicFile::writeAll can write it with every write checked.
class MemoryArchive : public openvdb::io::Archive {
 public:
  std::string encode(const openvdb::GridCPtrVec& grids) const {
    std::ostringstream out(std::ios_base::out | std::ios_base::binary);
    Archive::write(out, grids, /*seekable=*/true);
    return std::move(out).str();
  }
};

constexpr float kInactiveTolerance = 1e-6f;

void initializeOpenVdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

bool hasVdbMagic(const std::filesystem::path& path) {
  int64_t magic = 0;  // the format is little-endian
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(&magic), sizeof(magic));
  return in && magic == openvdb::OPENVDB_MAGIC;
}

// Reads through a stream that throws on a short read: io::File hands the missing bytes of a truncated file
// to the decompressor, which crashes.
openvdb::GridPtrVec loadGrids(const std::filesystem::path& path) {
  const std::string source = path.string();
  requireRegularFile(path);
  if (!hasVdbMagic(path)) throw InputError(source, "not a VDB file (no OpenVDB magic number)");
  initializeOpenVdb();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(source, "cannot open the file for reading");
  in.exceptions(std::ios::failbit | std::ios::badbit);
  try {
    openvdb::io::Stream stream(in, /*delayLoad=*/false);
    return *stream.getGrids();
  } catch (const std::ios_base::failure&) {
    throw InputError(source, in.eof() ? "truncated VDB file (the data ends early)" : "cannot read the file");
  } catch (const std::exception& error) {
    throw InputError(source, "corrupt VDB file: " + oneLine(error.what()));
  }
}

std::string gridNames(const openvdb::GridPtrVec& grids) {
  std::string list;
  for (const auto& grid : grids) list += (list.empty() ? "" : ", ") + grid->getName();
  return list;
}

openvdb::GridBase::Ptr findGrid(const openvdb::GridPtrVec& grids, std::string_view name) {
  const auto found =
      std::find_if(grids.begin(), grids.end(), [&](const auto& grid) { return grid->getName() == name; });
  return found == grids.end() ? nullptr : *found;
}

glm::vec3 toGlm(const openvdb::Vec3d& v) {
  return glm::vec3(v.x(), v.y(), v.z());
}

struct WorldBox {
  glm::vec3 min{std::numeric_limits<float>::max()};
  glm::vec3 max{std::numeric_limits<float>::lowest()};
  void extend(const WorldBox& other) {
    min = glm::min(min, other.min);
    max = glm::max(max, other.max);
  }
};

// The world box covered by the voxels of `indexBox`: voxel centres sit at integer index coordinates, so a
// voxel spans +-0.5 around them. All 8 corners are mapped, which also holds for rotating transforms.
WorldBox worldBoxOf(const openvdb::math::Transform& transform, const openvdb::CoordBBox& indexBox) {
  const openvdb::Vec3d lo = indexBox.min().asVec3d() - 0.5, hi = indexBox.max().asVec3d() + 0.5;
  WorldBox box;
  for (int corner = 0; corner < 8; ++corner) {
    const openvdb::Vec3d index(corner & 1 ? hi.x() : lo.x(), corner & 2 ? hi.y() : lo.y(),
                               corner & 4 ? hi.z() : lo.z());
    const glm::vec3 world = toGlm(transform.indexToWorld(index));
    box.min = glm::min(box.min, world);
    box.max = glm::max(box.max, world);
  }
  return box;
}

VdbGridInfo describe(const openvdb::GridBase& grid) {
  VdbGridInfo info;
  info.name = grid.getName();
  info.valueType = grid.valueType();
  info.gridClass = openvdb::GridBase::gridClassToString(grid.getGridClass());
  info.voxelSize = toGlm(grid.voxelSize());
  info.activeVoxelCount = static_cast<int64_t>(grid.activeVoxelCount());
  info.empty = info.activeVoxelCount == 0;
  if (!info.empty) {
    const openvdb::CoordBBox indexBox = grid.evalActiveVoxelBoundingBox();
    info.indexMin = glm::ivec3(indexBox.min().x(), indexBox.min().y(), indexBox.min().z());
    info.indexMax = glm::ivec3(indexBox.max().x(), indexBox.max().y(), indexBox.max().z());
    const WorldBox world = worldBoxOf(grid.transform(), indexBox);
    info.worldMin = world.min;
    info.worldMax = world.max;
  }
  return info;
}

// An empty dense grid (no values yet) laid out as the request says; `activeBox` is used by AutoBounds.
DenseGrid makeLattice(const DenseRequest& request, const WorldBox& activeBox) {
  DenseGrid dense;
  if (const auto* explicitBounds = std::get_if<ExplicitBounds>(&request)) {
    if (glm::any(glm::lessThanEqual(explicitBounds->cells, glm::ivec3(0))) ||
        glm::any(glm::lessThanEqual(explicitBounds->worldMax, explicitBounds->worldMin))) {
      throw std::invalid_argument("dense request: explicit bounds need cells > 0 and worldMax > worldMin");
    }
    dense.size = explicitBounds->cells;
    dense.origin = explicitBounds->worldMin;
    dense.dx = (explicitBounds->worldMax - explicitBounds->worldMin) / glm::vec3(explicitBounds->cells);
  } else {
    const int longestAxisCells = std::get<AutoBounds>(request).longestAxisCells;
    if (longestAxisCells <= 0) throw std::invalid_argument("dense request: longestAxisCells must be > 0");
    const glm::vec3 extent = activeBox.max - activeBox.min;
    const float cell = std::max({extent.x, extent.y, extent.z}) / static_cast<float>(longestAxisCells);
    // The small slack keeps rounding from adding a cell along the longest axis.
    const glm::vec3 cells = glm::max(glm::ceil(extent / cell - 1e-4f), glm::vec3(1.0f));
    dense.size = glm::ivec3(cells);
    dense.origin = activeBox.min;
    dense.dx = glm::vec3(cell);
  }
  return dense;
}

// Trilinear samples of `grid` at the world position of each cell centre.
void resample(const openvdb::FloatGrid& grid, DenseGrid& dense) {
  dense.values.assign(static_cast<std::size_t>(dense.size.x) * dense.size.y * dense.size.z, 0.0f);
  const glm::dvec3 origin(dense.origin), dx(dense.dx);
  tbb::parallel_for(tbb::blocked_range<int>(0, dense.size.z), [&](const tbb::blocked_range<int>& slices) {
    // One accessor per task (accessors cache nodes and are not thread-safe); the sampler keeps a pointer to
    // it.
    const openvdb::FloatGrid::ConstAccessor accessor = grid.getConstAccessor();
    const openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler> sampler(
        accessor, grid.transform());
    for (int k = slices.begin(); k != slices.end(); ++k) {
      for (int j = 0; j < dense.size.y; ++j) {
        for (int i = 0; i < dense.size.x; ++i) {
          const glm::dvec3 centre = origin + (glm::dvec3(i, j, k) + 0.5) * dx;
          dense.at(i, j, k) = sampler.wsSample(openvdb::Vec3d(centre.x, centre.y, centre.z));
        }
      }
    }
  });
}

bool holdsNonZero(const openvdb::FloatGrid& grid) {
  for (auto value = grid.cbeginValueOn(); value; ++value)
    if (*value != 0.0f) return true;
  return false;
}

// Why a grid holding smoke resampled to zeros: its voxels lie between the lattice's samples, as when a few
// voxels far apart stretch the lattice to cells thousands of voxels wide.
std::string missedBetweenSamples(const openvdb::FloatGrid& grid, const DenseGrid& dense) {
  const float voxel = static_cast<float>(grid.voxelSize()[0]);
  const float cell = std::max({dense.dx.x, dense.dx.y, dense.dx.z});
  return "grid '" + grid.getName() + "' holds nonzero voxels, but every sample of the " +
         std::to_string(dense.size.x) + "×" + std::to_string(dense.size.y) + "×" +
         std::to_string(dense.size.z) + " lattice falls between them (cells of " + show(cell) + " m, " +
         show(cell / voxel) +
         " voxels wide): the frame is empty (a scene can frame the smoke with vdb.box_min/box_max)";
}

void requireWritable(const std::string& source, const std::string& name, const DenseGrid* grid) {
  const std::string where = "grid '" + name + "': ";
  if (!grid) throw InputError(source, where + "no data");
  if (glm::any(glm::lessThanEqual(grid->size, glm::ivec3(0)))) {
    throw InputError(source, where + "has no cells");
  }
  const std::size_t count = static_cast<std::size_t>(grid->size.x) * grid->size.y * grid->size.z;
  if (grid->values.size() != count) {
    throw InputError(source, where + std::to_string(grid->values.size()) + " values for " +
                                 std::to_string(count) + " cells");
  }
  const float largest = std::max({grid->dx.x, grid->dx.y, grid->dx.z});
  const float smallest = std::min({grid->dx.x, grid->dx.y, grid->dx.z});
  if (!(smallest > 0.0f) || largest - smallest > 1e-5f * largest) {
    throw InputError(source, where + "cell size (" + std::to_string(grid->dx.x) + ", " +
                                 std::to_string(grid->dx.y) + ", " + std::to_string(grid->dx.z) +
                                 ") is not cubic, which VDB output needs");
  }
}

openvdb::FloatGrid::Ptr toFogVolume(const std::string& name, const DenseGrid& dense) {
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  grid->setName(name);
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  // Voxel centres sit at integer index coordinates, so index (i, j, k) maps to origin + (i + 0.5) * dx.
  const openvdb::math::Transform::Ptr transform = openvdb::math::Transform::createLinearTransform(dense.dx.x);
  const glm::dvec3 firstCentre = glm::dvec3(dense.origin) + 0.5 * glm::dvec3(dense.dx);
  transform->postTranslate(openvdb::Vec3d(firstCentre.x, firstCentre.y, firstCentre.z));
  grid->setTransform(transform);
  openvdb::FloatGrid::Accessor accessor = grid->getAccessor();
  for (int k = 0; k < dense.size.z; ++k) {
    for (int j = 0; j < dense.size.y; ++j) {
      for (int i = 0; i < dense.size.x; ++i) {
        const float value = dense.at(i, j, k);
        if (std::abs(value) > kInactiveTolerance) accessor.setValue(openvdb::Coord(i, j, k), value);
      }
    }
  }
  return grid;
}

}  // namespace

VdbFile readVdbInfo(const std::filesystem::path& path) {
  VdbFile file;
  file.path = path;
  for (const auto& grid : loadGrids(path)) file.grids.push_back(describe(*grid));
  return file;
}

DenseGrid readVdbDense(const std::filesystem::path& path, std::string_view gridName,
                       const DenseRequest& request) {
  const std::string source = path.string();
  const openvdb::GridPtrVec grids = loadGrids(path);
  const openvdb::GridBase::Ptr grid = findGrid(grids, gridName);
  if (!grid) {
    throw InputError(source,
                     "no grid '" + std::string(gridName) + "' (the file has: " + gridNames(grids) + ")");
  }
  const openvdb::FloatGrid::Ptr floatGrid = openvdb::gridPtrCast<openvdb::FloatGrid>(grid);
  if (!floatGrid) {
    throw InputError(source, "grid '" + grid->getName() + "' is " + grid->valueType() + ", not float");
  }
  const VdbGridInfo info = describe(*floatGrid);
  if (info.empty && std::holds_alternative<AutoBounds>(request)) {
    throw InputError(source, "grid '" + info.name + "' is empty: no active voxels to take bounds from");
  }
  DenseGrid dense = makeLattice(request, WorldBox{info.worldMin, info.worldMax});
  resample(*floatGrid, dense);
  return dense;
}

VdbDenseGrids readVdbGrids(const std::filesystem::path& path, const std::vector<std::string>& names,
                           const DenseRequest& request) {
  const std::string source = path.string();
  const openvdb::GridPtrVec grids = loadGrids(path);
  std::vector<std::string> wanted = names;
  if (wanted.empty()) {
    for (const auto& grid : grids) wanted.push_back(grid->getName());
  }

  VdbDenseGrids result;
  std::vector<openvdb::FloatGrid::Ptr> kept;
  WorldBox activeBox;
  for (const std::string& name : wanted) {
    const openvdb::GridBase::Ptr grid = findGrid(grids, name);
    const openvdb::FloatGrid::Ptr floatGrid = openvdb::gridPtrCast<openvdb::FloatGrid>(grid);
    if (!grid) {
      result.notes.push_back(source + ": no grid '" + name + "': skipped");
    } else if (!floatGrid) {
      result.notes.push_back(source + ": grid '" + name + "' is " + grid->valueType() +
                             ", not float: skipped");
    } else if (const VdbGridInfo info = describe(*floatGrid); info.empty) {
      result.notes.push_back(source + ": grid '" + name + "' is empty: skipped");
    } else {
      kept.push_back(floatGrid);
      activeBox.extend(WorldBox{info.worldMin, info.worldMax});
    }
  }
  if (kept.empty()) return result;

  const DenseGrid lattice = makeLattice(request, activeBox);
  for (const auto& grid : kept) {
    DenseGrid dense = lattice;
    resample(*grid, dense);
    if (std::ranges::all_of(dense.values, [](float v) { return v == 0.0f; }) && holdsNonZero(*grid))
      result.notes.push_back(source + ": " + missedBetweenSamples(*grid, dense));
    result.grids[grid->getName()] = std::move(dense);
  }
  return result;
}

void writeVdb(const std::filesystem::path& path,
              const std::vector<std::pair<std::string, const DenseGrid*>>& grids) {
  const std::string source = path.string();
  for (std::size_t g = 0; g < grids.size(); ++g) {
    const std::string& name = grids[g].first;
    const bool repeated =
        std::any_of(grids.begin(), grids.begin() + g, [&](const auto& other) { return other.first == name; });
    if (name.empty() || repeated) throw InputError(source, "grid name '" + name + "' is empty or repeated");
    requireWritable(source, name, grids[g].second);
  }

  initializeOpenVdb();
  openvdb::GridCPtrVec fogVolumes;
  for (const auto& [name, dense] : grids) fogVolumes.push_back(toFogVolume(name, *dense));

  std::string encoded;
  try {
    encoded = MemoryArchive().encode(fogVolumes);
  } catch (const std::exception& error) {
    throw InputError(source, "cannot write VDB: " + oneLine(error.what()));
  }
  AtomicFile file(path);
  file.writeAll(std::span(reinterpret_cast<const uint8_t*>(encoded.data()), encoded.size()));
  file.commit();
}

}  // namespace sixway::io
