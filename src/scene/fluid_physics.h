#pragma once
// What a simulated scene's settings imply for its flow, in world units: the speeds that fix the time step,
// the viscosity, and the LBM steps per frame (the lattice units themselves: sim/lattice_units.h).
#include "scene/scene.h"

namespace sixway::scene {

// The speed that fixes the time step and the Reynolds number: the fastest inlet, or the wind when a
// face is inflow, in m/s.
float referenceSpeed(const Scene& scene);
// m²/s: the given viscosity, or referenceSpeed · referenceLength / reynolds.
float kinematicViscosity(const Scene& scene);
// The fastest a buoyant plume can get, m/s: free fall through the domain's height along gravity under the
// strongest buoyant acceleration an inlet injects, sqrt(2 · a · H) (0 without buoyancy).
float buoyantSpeedBound(const Scene& scene);
// Steps per frame that bring the fastest inflow down to fluid.max_lattice_velocity and the buoyant plume's
// speed bound down to 0.25 cells per step: lattice speed = speed · (frameDt / steps) / cellSize. Not rounded
// to an int, so that a scene needing more than kMaxStepsPerFrame is refused rather than overflowing.
double stepsForLatticeVelocity(const Scene& scene);
// LBM steps per frame: time.stepsPerFrame, or more if stepsForLatticeVelocity needs more.
int lbmStepsPerFrame(const Scene& scene);

}  // namespace sixway::scene
