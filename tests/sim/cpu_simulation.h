#pragma once
// CPU oracle: the whole simulation step of a scene in lattice units (cell_size 1, origin 0, one second
// per lattice step), composed from the oracles of this folder in the order the frame runs them:
// cell flags from the obstacles and inlets at this step → LBM step (smoke of the last step drives the
// buoyancy) → smoke sources → smoke transport by the new velocity.
// Obstacles: sphere, cylinder and box (meshes are tested on their own), static or moving along
// keyframes (linear in between, held outside them). Inlets: disk and box, without noise.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "cpu_fct.h"
#include "cpu_lbm.h"
#include "cpu_shapes.h"
#include "scene/scene.h"

namespace sixway::test {

class CpuSimulation {
 public:
  explicit CpuSimulation(const scene::Scene& scene);

  // Velocity and density per lattice cell; populations at their equilibrium.
  void setFlow(const std::vector<glm::dvec3>& velocity, const std::vector<double>& density);
  void setSmoke(std::vector<glm::dvec2> smoke) { smoke_ = std::move(smoke); }
  void advance(int steps);

  // What the obstacles and inlets make of the grid at `step`, given the flags of the step before.
  CpuStepInputs inputsAt(uint64_t step, const std::vector<CellFlags>& previous) const;
  // The smallest distance of a cell centre from an obstacle's surface at `step`: a scene whose cells
  // all lie farther than float rounding (1e-3 cells) is decided the same way by the GPU.
  double surfaceMargin(uint64_t step) const;

  const CpuLbm& lbm() const { return lbm_; }
  const std::vector<CellFlags>& flags() const { return flags_; }  // of the last step

 private:
  struct Motion {
    glm::dvec3 position, velocity;
  };
  Motion obstacleAt(size_t obstacle, double time) const;

  scene::Scene scene_;
  CpuLbm lbm_;
  CpuSmokeSettings smokeSettings_;
  std::vector<glm::dvec2> smoke_;
  std::vector<CellFlags> flags_;
  uint64_t step_ = 0;
};

// The LBM settings of a lattice-unit scene, from the scene format's definitions.
CpuLbmSettings cpuLbmSettings(const scene::Scene& scene);

}  // namespace sixway::test
