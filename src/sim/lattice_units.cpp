#include "sim/lattice_units.h"

#include "scene/fluid_physics.h"

namespace sixway::sim {

LatticeUnits latticeUnits(const scene::Scene& scene) {
  LatticeUnits u;
  u.cellSize = scene.grid.cellSize;
  u.stepsPerFrame = scene::lbmStepsPerFrame(scene);
  u.stepSeconds = scene.time.frameDt / float(u.stepsPerFrame);
  u.velocityScale = u.stepSeconds / u.cellSize;
  u.accelerationScale = u.stepSeconds * u.stepSeconds / u.cellSize;
  const float nuLattice = scene::kinematicViscosity(scene) * u.stepSeconds / (u.cellSize * u.cellSize);
  u.tau = 3.0f * nuLattice + 0.5f;
  return u;
}

}  // namespace sixway::sim
