#include "render/volume.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "io/dense_grid.h"
#include "io/error.h"

namespace sixway::render {

void requireConsistent(const Volume& volume) {
  const VolumeGrid& g = volume.grid;
  const uint64_t bytes = g.cellCount() * sizeof(float);
  if (!volume.density || g.size.x < 1 || g.size.y < 1 || g.size.z < 1 || !(g.cellSize > 0.0f) ||
      volume.density->size() < bytes || (volume.temperature && volume.temperature->size() < bytes))
    throw std::invalid_argument("volume: the buffers do not hold its " + std::to_string(g.size.x) + "x" +
                                std::to_string(g.size.y) + "x" + std::to_string(g.size.z) + " cells");
}

DeviceVolume::DeviceVolume(const gpu::Context& context, const VolumeGrid& grid, bool withTemperature)
    : grid_(grid), hasTemperature_(withTemperature) {
  const uint64_t bytes = grid.cellCount() * sizeof(float);
  density_ = gpu::Buffer::storage(context, bytes, "density volume");
  if (withTemperature) temperature_ = gpu::Buffer::storage(context, bytes, "temperature volume");
}

void DeviceVolume::upload(std::span<const float> density, std::span<const float> temperature) {
  const uint64_t cells = grid_.cellCount();
  if (density.size() != cells || (!temperature.empty() && temperature.size() != cells))
    throw std::invalid_argument("DeviceVolume::upload: " + std::to_string(density.size()) + " density and " +
                                std::to_string(temperature.size()) + " temperature values for " +
                                std::to_string(cells) + " cells");
  density_.upload(std::as_bytes(density));
  if (!hasTemperature_) return;
  if (temperature.empty()) {
    temperature_.upload(std::vector<float>(cells, 0.0f));
  } else {
    temperature_.upload(std::as_bytes(temperature));
  }
}

Volume DeviceVolume::view() const {
  return {grid_, &density_, hasTemperature_ ? &temperature_ : nullptr};
}

VolumeGrid volumeGridOf(const io::DenseGrid& grid, std::string_view source) {
  const float dx = grid.dx.x;
  auto same = [dx](float d) { return std::fabs(d - dx) <= 1e-5f * dx; };
  if (!(dx > 0) || !same(grid.dx.y) || !same(grid.dx.z))
    throw io::InputError(source, "cells are not cubic (" + std::to_string(grid.dx.x) + " x " +
                                     std::to_string(grid.dx.y) + " x " + std::to_string(grid.dx.z) +
                                     "); resample onto cubic cells first");
  return {grid.size, grid.origin, dx};
}

DeviceVolume uploadVolume(const gpu::Context& context, const io::DenseGrid& density,
                          const io::DenseGrid* temperature, std::string_view source) {
  const VolumeGrid grid = volumeGridOf(density, source);
  if (temperature && (temperature->size != density.size || temperature->origin != density.origin ||
                      temperature->dx != density.dx))
    throw io::InputError(source, "the temperature grid is not on the density grid's lattice");
  DeviceVolume volume(context, grid, temperature != nullptr);
  volume.upload(density.values,
                temperature ? std::span<const float>(temperature->values) : std::span<const float>());
  return volume;
}

}  // namespace sixway::render
