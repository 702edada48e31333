#include "scene/fluid_physics.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace sixway::scene {
namespace {

// The lattice speed the buoyant plume's speed bound may reach: under the watchdog's stable limit (0.35,
// sim/watchdog.h) with a margin; the bound is free fall, which drag and mixing keep the real plume below.
constexpr double kBuoyantLatticeVelocity = 0.25;

}  // namespace

float referenceSpeed(const Scene& scene) {
  float speed = 0;
  for (const Inlet& inlet : scene.inlets) speed = std::max(speed, glm::length(inlet.velocity));
  if (std::ranges::count(scene.boundaries.faces, BoundaryType::Inflow) > 0)
    speed = std::max(speed, glm::length(scene.boundaries.wind));
  return speed;
}

float kinematicViscosity(const Scene& scene) {
  const Fluid& f = scene.fluid;
  return f.viscosity ? *f.viscosity : referenceSpeed(scene) * f.referenceLength / *f.reynolds;
}

float buoyantSpeedBound(const Scene& scene) {
  float acceleration = 0;
  for (const Inlet& inlet : scene.inlets)
    acceleration = std::max(acceleration, std::abs(scene.fluid.buoyancy.temperature * inlet.temperature +
                                                   scene.fluid.buoyancy.density * inlet.density));
  const glm::vec3 up = glm::abs(glm::normalize(scene.fluid.gravity));
  const float height = glm::dot(up, glm::vec3(scene.grid.size) * scene.grid.cellSize);
  return std::sqrt(2.0f * acceleration * height);
}

double stepsForLatticeVelocity(const Scene& scene) {
  const double step = double(scene.time.frameDt) / scene.grid.cellSize;
  return std::max(std::ceil(step * referenceSpeed(scene) / scene.fluid.maxLatticeVelocity),
                  std::ceil(step * buoyantSpeedBound(scene) / kBuoyantLatticeVelocity));
}

int lbmStepsPerFrame(const Scene& scene) {
  return std::max(scene.time.stepsPerFrame, static_cast<int>(stepsForLatticeVelocity(scene)));
}

}  // namespace sixway::scene
