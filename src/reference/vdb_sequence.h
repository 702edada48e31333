#pragma once
// A sequence of OpenVDB files, one frame each, resampled onto one lattice of cubic cells that covers the
// active voxels of every file (so that non-uniform voxel sizes and transforms are honoured, and every frame
// shares the same buffers). Files whose density grid is missing or empty are empty frames.
#include <filesystem>
#include <string>
#include <vector>

#include "render/volume.h"
#include "render/volume_sequence.h"

namespace sixway::gpu {
class Context;
}

namespace sixway::render {

class VdbSequence : public VolumeSequence {
 public:
  // Reads every file's grid list up front (so a missing or corrupt file fails before any work) and sizes the
  // lattice: `longestAxisCells` cells along the longest axis of the union of the grids' world boxes. With
  // `withTemperature`, a float grid named "temperature" (else "heat") becomes the temperature.
  VdbSequence(const gpu::Context& context, std::vector<std::filesystem::path> files, int longestAxisCells,
              bool withTemperature);

  int frameCount() const override { return int(files_.size()); }
  std::optional<Volume> frame(int index) override;
  Box bounds() const override { return lattice_.bounds(); }
  std::string frameName(int index) const override { return files_[index].filename().string(); }

  const VolumeGrid& lattice() const { return lattice_; }
  // What the reader skipped so far ("<file>: grid 'obstacles' is int32, not float: skipped").
  const std::vector<std::string>& notes() const { return notes_; }

 private:
  std::vector<std::filesystem::path> files_;
  bool withTemperature_;
  VolumeGrid lattice_;
  DeviceVolume volume_;
  std::vector<std::string> notes_;
};

}  // namespace sixway::render
