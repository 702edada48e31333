#pragma once
// The D3Q19 lattice and its kernels (shaders/sim/lbm_*.comp, forces*.comp): two lattices, each
// in four structure-of-arrays buffers, swapped every step (pull streaming reads one, writes the other), of
// 32-bit populations or of 16-bit shifted ones (io::PopulationStorage, lbm_lattice.glsl).
#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <utility>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/pipeline.h"
#include "io/scene.h"
#include "sim/lattice_units.h"

namespace sixway::gpu {
class Sequence;
}

namespace sixway::sim {

struct LbmSettings {
  glm::ivec3 size{0};
  std::array<io::BoundaryType, 6> faces{};
  float tau = 0.6f;
  float smagorinsky = 0;
  int smokeUpres = 1;
  float buoyancyTemperature = 0, buoyancyDensity = 0;  // lattice acceleration per unit
  glm::vec3 up{0, 1, 0};
  glm::vec3 bodyForce{0};  // lattice acceleration
  glm::vec3 wind{0};       // lattice velocity on inflow faces
  bool parabolicInflow = false;
  bool interpolatedBounceBack = false;  // obstacles: io::ObstacleBoundary::Interpolated
  io::PopulationStorage storage = io::PopulationStorage::Fp32;
};

// Bytes of one stored population.
uint32_t populationBytes(io::PopulationStorage storage);
// Bytes read and written per cell update by lbm_step: 19 populations each way, the flags and the macro state
// (read and written); the smoke and the neighbours' flags are left out.
uint32_t bytesPerCellUpdate(io::PopulationStorage storage);
// Device memory of a lattice of `cells` cells: both population sets and the macro state (16 bytes a cell).
uint64_t latticeBytes(uint64_t cells, io::PopulationStorage storage);

LbmSettings lbmSettings(const io::Scene& scene, const LatticeUnits& units);

class LbmSolver {
 public:
  LbmSolver(const gpu::Context& context, const gpu::PipelineCache& cache, const LbmSettings& settings);

  // Sets the populations of lattice `parity` to the equilibrium of `macro` (velocity xyz, density w
  // per cell) and keeps `macro` as the current macroscopic state. Blocks.
  void initialize(const std::vector<glm::vec4>& macro, int parity);
  // One step: stream from lattice `parity`, collide, write lattice 1 − parity and the macro state. `box`
  // ([min, max), ObstacleSet::sweptBox) holds every cell next to an obstacle: those, and the cells on the
  // lattice's faces, are updated by a second dispatch with the boundary conditions.
  void recordStep(gpu::Sequence& sequence, const gpu::Buffer& params, const gpu::Buffer& flags,
                  const gpu::Buffer& smoke, uint32_t slot, int parity,
                  const std::pair<glm::ivec3, glm::ivec3>& box) const;
  // Momentum-exchange force on each obstacle before the step that streams from lattice `parity`,
  // added into forces[slot · kMaxObstacles + obstacle] (vec4; zero it before). Only the cells of `box`
  // ([min, max), ObstacleSet::sweptBox) are visited: no link to an obstacle lies outside it.
  void recordForces(gpu::Sequence& sequence, const gpu::Buffer& params, const gpu::Buffer& flags,
                    uint32_t slot, int parity, const gpu::Buffer& forces,
                    const std::pair<glm::ivec3, glm::ivec3>& box) const;

  const gpu::Buffer& macro() const { return macro_; }
  // Read-only view of lattice `parity`'s populations, buffer b of 4 (lbm_lattice.glsl), for tests.
  const gpu::Buffer& lattice(int parity, int buffer) const { return lattices_[parity][buffer]; }
  uint64_t cells() const { return cells_; }
  io::PopulationStorage storage() const { return settings_.storage; }

 private:
  const gpu::Context* context_;
  LbmSettings settings_;
  uint64_t cells_;
  std::array<std::array<gpu::Buffer, 4>, 2> lattices_;
  gpu::Buffer macro_;
  // The step's pipelines (lbm_step.comp): the interior; the face slabs and the obstacles' box in one (when
  // the box reaches a face) or each on its own.
  std::unique_ptr<gpu::Pipeline> init_, step_, stepBoundary_, stepFaces_, stepObstacles_, forces_;
};

}  // namespace sixway::sim
