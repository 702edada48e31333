#pragma once
// The D3Q19 lattice and its kernels (shaders/sim/lbm_*.comp, forces*.comp): one set of populations, in four
// structure-of-arrays buffers, streamed in place by steps of alternating parity (lbm_in_place.glsl), of
// 32-bit populations or of 16-bit shifted ones (scene::PopulationStorage, lbm_lattice.glsl).
#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/pipeline.h"
#include "scene/scene.h"
#include "sim/lattice_units.h"

namespace sixway::gpu {
class Sequence;
}

namespace sixway::sim {

struct LbmSettings {
  glm::ivec3 size{0};
  std::array<scene::BoundaryType, 6> faces{};
  float tau = 0.6f;
  float smagorinsky = 0;
  int smokeUpres = 1;
  float buoyancyTemperature = 0, buoyancyDensity = 0;  // lattice acceleration per unit
  glm::vec3 up{0, 1, 0};
  glm::vec3 bodyForce{0};  // lattice acceleration
  glm::vec3 wind{0};       // lattice velocity on inflow faces
  bool parabolicInflow = false;
  bool interpolatedBounceBack = false;  // obstacles: scene::ObstacleBoundary::Interpolated
  scene::PopulationStorage storage = scene::PopulationStorage::Fp32;
};

// Bytes of one stored population.
uint32_t populationBytes(scene::PopulationStorage storage);
// Bytes read and written per cell update by lbm_step: 19 populations each way, the flags and the macro state
// (read and written); the smoke and the neighbours' flags are left out.
uint32_t bytesPerCellUpdate(scene::PopulationStorage storage);
// The cells stored for a lattice of `size` cells: a ghost layer across every face that is not periodic
// (lbm_in_place.glsl).
glm::ivec3 storedSize(glm::ivec3 size, const std::array<scene::BoundaryType, 6>& faces);
// Device memory of a lattice: its populations (ghost cells included) and the macro state (16 bytes a cell).
uint64_t latticeBytes(glm::ivec3 size, const std::array<scene::BoundaryType, 6>& faces,
                      scene::PopulationStorage storage);

LbmSettings lbmSettings(const scene::Scene& scene, const LatticeUnits& units);

// A pipeline per step parity, built the first time it is recorded: lavapipe compiles a pipeline when it is
// created, and a lattice uses only some (without obstacles: no forces, box or uncovered pipelines). The
// pipeline cache must outlive it.
class ParityPipelines {
 public:
  ParityPipelines() = default;
  ParityPipelines(const gpu::Context& context, const gpu::PipelineCache& cache,
                  gpu::ComputePipelineDesc desc);
  const gpu::Pipeline& operator[](int parity);

 private:
  const gpu::Context* context_ = nullptr;
  const gpu::PipelineCache* cache_ = nullptr;
  gpu::ComputePipelineDesc desc_;
  std::array<std::unique_ptr<gpu::Pipeline>, 2> built_;
};

class LbmSolver {
 public:
  LbmSolver(const gpu::Context& context, const gpu::PipelineCache& cache, const LbmSettings& settings);

  // Sets the populations to the equilibrium of `macro` (velocity xyz, density w per cell), kept for a step
  // of parity `parity`, and keeps `macro` as the current macroscopic state. Blocks.
  void initialize(const std::vector<glm::vec4>& macro, int parity);
  // One step of parity `parity` (the next one is of the other): stream, collide, write the populations in
  // place and the macro state. `box` ([min, max), ObstacleSet::sweptBox) holds every cell next to an
  // obstacle: those, and the cells on the lattice's faces, are updated by further dispatches with the
  // boundary conditions.
  void recordStep(gpu::Sequence& sequence, const gpu::Buffer& params, const gpu::Buffer& flags,
                  const gpu::Buffer& smoke, uint32_t slot, int parity,
                  const std::pair<glm::ivec3, glm::ivec3>& box);
  // Momentum-exchange force on each obstacle before the step of parity `parity`, added into
  // forces[slot · kMaxObstacles + obstacle] (vec4; zero it before). Only the cells of `box` ([min, max),
  // ObstacleSet::sweptBox) are visited: no link to an obstacle lies outside it.
  void recordForces(gpu::Sequence& sequence, const gpu::Buffer& params, const gpu::Buffer& flags,
                    uint32_t slot, int parity, const gpu::Buffer& forces,
                    const std::pair<glm::ivec3, glm::ivec3>& box);

  const gpu::Buffer& macro() const { return macro_; }
  // Read-only view of the populations, buffer b of 4 (lbm_lattice.glsl; which slot holds which population
  // after which step: lbm_in_place.glsl), for tests.
  const gpu::Buffer& lattice(int buffer) const { return lattice_[buffer]; }
  glm::ivec3 size() const { return settings_.size; }
  // Cells per axis as stored: the lattice and its ghost layers.
  glm::ivec3 storedSize() const { return storedSize_; }
  uint64_t cells() const { return cells_; }
  scene::PopulationStorage storage() const { return settings_.storage; }

 private:
  // Four buffers of populations 0–4, 5–9, 10–14, 15–18 for `cells` cells (lbm_lattice.glsl).
  std::array<gpu::Buffer, 4> populationBuffers(uint64_t cells, const std::string& name) const;
  // The copy of the box cells' populations that interpolated bounce-back reads (lbm_keep_away.comp), for at
  // least `boxCells` cells.
  const std::array<gpu::Buffer, 4>& awayBuffers(uint64_t boxCells);

  const gpu::Context* context_;
  LbmSettings settings_;
  uint64_t cells_;
  glm::ivec3 storedSize_;
  std::array<gpu::Buffer, 4> lattice_;
  gpu::Buffer macro_;
  // Grown as the box grows; the smaller ones stay alive for sequences recorded with them (Simulation keeps
  // retired sequences until the frames that ran them are done).
  std::vector<std::array<gpu::Buffer, 4>> away_;
  // Per parity. The step's pipelines (lbm_step.comp): the interior; the face slabs and the obstacles' box in
  // one (when the box reaches a face) or each on its own; the cells uncovered by a moving obstacle.
  ParityPipelines init_, step_, stepBoundary_, stepFaces_, stepObstacles_, stepUncovered_, keepAway_, forces_;
};

}  // namespace sixway::sim
