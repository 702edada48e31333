#pragma once
// The scene's physical units (metres, seconds) mapped to lattice units (cells, steps).
// Lattice speed = speed · dt / dx, lattice acceleration = acceleration · dt² / dx,
// lattice viscosity = ν · dt / dx², relaxation time τ = 3 ν_lattice + ½.
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace sixway::sim {

struct LatticeUnits {
  float cellSize = 0;     // m
  float stepSeconds = 0;  // s per lattice step
  int stepsPerFrame = 1;
  float tau = 0;                // from the molecular viscosity
  float velocityScale = 0;      // (cells/step) per (m/s)
  float accelerationScale = 0;  // (cells/step²) per (m/s²)

  float toLatticeVelocity(float metresPerSecond) const { return metresPerSecond * velocityScale; }
  glm::vec3 toLatticeVelocity(glm::vec3 v) const { return v * velocityScale; }
  glm::vec3 toLatticeAcceleration(glm::vec3 a) const { return a * accelerationScale; }
  glm::vec3 toLattice(glm::vec3 world, glm::vec3 origin) const { return (world - origin) / cellSize; }
};

LatticeUnits latticeUnits(const scene::Scene& scene);

}  // namespace sixway::sim
