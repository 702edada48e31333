#pragma once
// A sequence of OpenVDB files resampled onto one lattice of cubic cells that covers the active voxels of
// every file (so that non-uniform voxel sizes and transforms are honoured, and every frame shares the same
// buffers), placed in the world by the scene's transform (scene::VdbSource). Files whose density grid is
// missing or empty are empty frames.
#include <filesystem>
#include <string>
#include <vector>

#include "io/vdb.h"
#include "render/volume.h"
#include "render/volume_sequence.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Context;
}

namespace sixway::reference {

class VdbSequence : public render::VolumeSequence {
 public:
  // Reads every file's grid list up front (so a missing or corrupt file fails before any work) and sizes the
  // lattice: source.voxels cells along the longest axis of the union of the grids' world boxes. Throws
  // InputError when no file has a usable density grid, or when the temperature grid is named but in no file.
  VdbSequence(const gpu::Context& context, scene::VdbSource source);
  // `sixway bake --vdb`: files as given, one frame each, their float grid `densityGrid` the density; with
  // `withTemperature`, a float grid named "temperature" (else "heat") becomes the temperature.
  VdbSequence(const gpu::Context& context, std::vector<std::filesystem::path> files, int longestAxisCells,
              bool withTemperature, std::string densityGrid = "density");

  int frameCount() const override { return int(source_.files.size()) * source_.framesPerFile; }
  // Unlike a simulation, frames may be asked for in any order (the demo loops them); a file is read again
  // only when the frame asked for is in another file than the last one.
  std::optional<render::Volume> frame(int index) override;
  render::Volume volume(int index) override;
  render::Box bounds() const override { return lattice_.bounds(); }
  std::string frameName(int index) const override { return file(index).filename().string(); }
  float cellSize() const override { return lattice_.cellSize; }
  // The largest density of the files of those frames as resampled (each read once more).
  float densityBound(int first, int count) override;

  const render::VolumeGrid& lattice() const { return lattice_; }
  const scene::VdbSource& source() const { return source_; }
  const std::filesystem::path& file(int frame) const { return source_.files[frame / source_.framesPerFile]; }
  // What the reader skipped or changed so far, each once ("<file>: grid 'obstacles' is int32, not float:
  // skipped").
  const std::vector<std::string>& notes() const { return notes_; }

 private:
  // Reads the file of `frame` into the buffers unless it is there already; false for an empty frame.
  bool load(int frame);
  // Grids `names` of file `fileIndex` on the lattice, in the file's axes; its notes kept, each once.
  io::VdbDenseGrids read(int fileIndex, const std::vector<std::string>& names);

  scene::VdbSource source_;
  std::vector<std::string> notes_;  // before lattice_: sizing the lattice adds notes
  render::VolumeGrid lattice_;
  render::DeviceVolume volume_;
  int loadedFile_ = -1;
  bool loadedEmpty_ = true;
};

}  // namespace sixway::reference
