#pragma once
// Volumes as the reference renderers read them: a density buffer (and optionally a temperature buffer) on
// the GPU over a dense lattice of cubic cells. The simulation hands over its own buffers each frame;
// volumes read from files live in a DeviceVolume.
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <string_view>

#include "gpu/buffer.h"

namespace sixway::io {
struct DenseGrid;
}

namespace sixway::render {

// An axis-aligned box in world space.
struct Box {
  glm::vec3 min{0.0f}, max{0.0f};
  glm::vec3 size() const { return max - min; }
  glm::vec3 centre() const { return 0.5f * (min + max); }
};

// Cell (i, j, k) has its centre at origin + (i + 0.5, j + 0.5, k + 0.5) · cellSize; values are stored x
// fastest, then y, then z. Between cell centres values are trilinear, between the outer centres and the box
// faces they are those of the outer cells (clamped), and outside the box they are zero.
struct VolumeGrid {
  glm::ivec3 size{0};
  glm::vec3 origin{0.0f};  // world position of the corner of cell (0, 0, 0)
  float cellSize = 0.0f;   // metres

  uint64_t cellCount() const { return uint64_t(size.x) * uint64_t(size.y) * uint64_t(size.z); }
  Box bounds() const { return {origin, origin + glm::vec3(size) * cellSize}; }
};

// A volume on the GPU, borrowed: the buffers belong to whoever hands it over and must hold
// grid.cellCount() floats and stay alive while work recorded with them runs. Density is per unit of the
// optics' extinction (σ_t = extinction · density); negative values count as zero.
struct Volume {
  VolumeGrid grid;
  const gpu::Buffer* density = nullptr;
  const gpu::Buffer* temperature = nullptr;  // none: temperature 0 everywhere
};

// Throws std::invalid_argument unless the volume has a density buffer, a lattice with cells, and buffers that
// hold every cell.
void requireConsistent(const Volume& volume);

// Buffers for a volume of a fixed lattice, filled from the host (e.g. each frame of a VDB sequence).
class DeviceVolume {
 public:
  DeviceVolume(const gpu::Context& context, const VolumeGrid& grid, bool withTemperature);

  // Values x fastest; `temperature` is ignored without a temperature buffer and zero when empty.
  void upload(std::span<const float> density, std::span<const float> temperature = {});
  const VolumeGrid& grid() const { return grid_; }
  Volume view() const;
  // For GPU producers (the simulation's smoke export); the temperature buffer only withTemperature.
  const gpu::Buffer& density() const { return density_; }
  const gpu::Buffer& temperature() const { return temperature_; }

 private:
  VolumeGrid grid_;
  gpu::Buffer density_, temperature_;
  bool hasTemperature_;
};

// The lattice of a dense grid; throws io::InputError naming `source` unless its cells are cubic (read VDB
// files with cubic cells, e.g. io::AutoBounds, so that non-uniform voxel sizes are resampled).
VolumeGrid volumeGridOf(const io::DenseGrid& grid, std::string_view source);

// A density grid (and optionally a temperature grid on the same lattice) on the GPU.
DeviceVolume uploadVolume(const gpu::Context& context, const io::DenseGrid& density,
                          const io::DenseGrid* temperature = nullptr, std::string_view source = "volume");

}  // namespace sixway::render
