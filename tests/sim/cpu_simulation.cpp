#include "cpu_simulation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include "scene/fluid_physics.h"

namespace sixway::test {
namespace {

size_t cellCount(glm::ivec3 n) {
  return size_t(n.x) * n.y * n.z;
}

void requireLatticeUnits(const scene::Scene& scene) {
  const double stepSeconds = scene.time.frameDt / scene::lbmStepsPerFrame(scene);
  if (scene.grid.cellSize != 1 || stepSeconds != 1 || scene.grid.origin != glm::vec3(0))
    throw std::invalid_argument(
        "CpuSimulation: the scene must be in lattice units (cell 1 m, step 1 s, origin 0)");
}

bool insideInlet(const scene::Inlet& inlet, glm::dvec3 p) {
  if (const auto* disk = std::get_if<scene::InletDisk>(&inlet.shape)) {
    const glm::dvec3 d = p - glm::dvec3(disk->center), n(disk->normal);
    const double along = glm::dot(d, n);
    return along >= -0.5 && along < 0.5 && glm::length(d - along * n) <= disk->radius;
  }
  const auto& box = std::get<scene::InletBox>(inlet.shape);
  return glm::all(glm::greaterThanEqual(p, glm::dvec3(box.min))) &&
         glm::all(glm::lessThan(p, glm::dvec3(box.max)));
}

ShapeTest shapeTest(const scene::Obstacle& obstacle, glm::dvec3 centre, glm::dvec3 p) {
  const auto& shape = obstacle.shape;
  if (const auto* s = std::get_if<scene::SphereObstacle>(&shape)) return sphereTest(p, centre, s->radius);
  if (const auto* c = std::get_if<scene::CylinderObstacle>(&shape))
    return cylinderTest(p, centre, glm::dvec3(c->axis), c->radius, 0.5 * c->height);
  if (const auto* c = std::get_if<scene::CapsuleObstacle>(&shape))
    return capsuleTest(p, centre, glm::dvec3(c->axis), c->radius, 0.5 * c->height - c->radius);
  if (const auto* b = std::get_if<scene::BoxObstacle>(&shape))
    return boxTest(p, centre, 0.5 * glm::dvec3(b->size));
  throw std::invalid_argument("CpuSimulation: mesh obstacles are not modelled");
}

}  // namespace

CpuLbmSettings cpuLbmSettings(const scene::Scene& scene) {
  requireLatticeUnits(scene);
  CpuLbmSettings s;
  s.size = scene.grid.size;
  s.faces = scene.boundaries.faces;
  s.tau = 3 * double(scene::kinematicViscosity(scene)) + 0.5;  // ν = c_s² (τ − ½)
  s.smagorinsky = scene.fluid.smagorinsky;
  s.smokeUpres = scene.grid.smokeUpres;
  s.buoyancyTemperature = scene.fluid.buoyancy.temperature;
  s.buoyancyDensity = scene.fluid.buoyancy.density;
  s.up = -glm::normalize(glm::dvec3(scene.fluid.gravity));
  s.bodyAcceleration = scene.fluid.bodyForce;
  s.wind = scene.boundaries.wind;
  s.parabolicInflow = scene.boundaries.inflowProfile == scene::InflowProfile::Parabolic;
  s.interpolatedBounceBack = scene.fluid.obstacleBoundary == scene::ObstacleBoundary::Interpolated;
  return s;
}

CpuSimulation::CpuSimulation(const scene::Scene& scene)
    : scene_(scene),
      lbm_(cpuLbmSettings(scene),
           std::vector<glm::dvec4>(cellCount(scene.grid.size), glm::dvec4(0, 0, 0, 1))),
      smokeSettings_{scene.grid.size, scene.grid.smokeUpres, scene.boundaries.faces},
      smoke_(cellCount(smokeSettings_.smokeSize()), glm::dvec2(0)),
      flags_(cellCount(scene.grid.size)) {
  for (const scene::Inlet& inlet : scene.inlets)
    if (inlet.noise != 0) throw std::invalid_argument("CpuSimulation: inlet noise is not modelled");
}

void CpuSimulation::setFlow(const std::vector<glm::dvec3>& velocity, const std::vector<double>& density) {
  std::vector<glm::dvec4> macro(velocity.size());
  for (size_t c = 0; c < macro.size(); ++c) macro[c] = glm::dvec4(velocity[c], density[c]);
  lbm_ = CpuLbm(lbm_.settings(), std::move(macro));
}

CpuSimulation::Motion CpuSimulation::obstacleAt(size_t obstacle, double time) const {
  const scene::Obstacle& o = scene_.obstacles[obstacle];
  if (!o.motion) {
    return {std::visit(
                [](const auto& shape) -> glm::dvec3 {
                  using T = std::decay_t<decltype(shape)>;
                  if constexpr (std::is_same_v<T, scene::MeshObstacle>)
                    return glm::dvec3(shape.translate);
                  else
                    return glm::dvec3(shape.center);
                },
                o.shape),
            glm::dvec3(0)};
  }
  const auto& keys = o.motion->keyframes;
  if (o.motion->loop) throw std::invalid_argument("CpuSimulation: looping motion is not modelled");
  if (time < keys.front().time) return {keys.front().position, glm::dvec3(0)};
  if (time >= keys.back().time) return {keys.back().position, glm::dvec3(0)};
  // At a keyframe's time the wall moves with the segment the coming step moves along (docs/scene-format.md).
  size_t k = 0;
  while (keys[k + 1].time <= time) ++k;
  const glm::dvec3 velocity = (glm::dvec3(keys[k + 1].position) - glm::dvec3(keys[k].position)) /
                              double(keys[k + 1].time - keys[k].time);
  return {glm::dvec3(keys[k].position) + velocity * (time - keys[k].time), velocity};
}

double CpuSimulation::surfaceMargin(uint64_t step) const {
  double margin = INFINITY;
  const glm::ivec3 n = scene_.grid.size;
  for (size_t o = 0; o < scene_.obstacles.size(); ++o) {
    const glm::dvec3 centre = obstacleAt(o, double(step)).position;
    for (int c = 0; c < n.x * n.y * n.z; ++c)
      margin =
          std::min(margin, shapeTest(scene_.obstacles[o], centre, glm::dvec3(cellOf(c, n)) + 0.5).margin);
  }
  return margin;
}

CpuStepInputs CpuSimulation::inputsAt(uint64_t step, const std::vector<CellFlags>& previous) const {
  const double time = double(step);
  CpuStepInputs in;
  std::vector<glm::dvec3> centres;
  for (size_t o = 0; o < scene_.obstacles.size(); ++o) {
    const Motion m = obstacleAt(o, time);
    centres.push_back(m.position);
    in.obstacleVelocity.push_back(m.velocity);
  }
  for (const scene::Inlet& inlet : scene_.inlets) in.inletVelocity.push_back(inlet.velocity);
  in.insideObstacle = [obstacles = scene_.obstacles, centres](int o, glm::dvec3 p) {
    return shapeTest(obstacles[o], centres[o], p).inside;
  };
  const glm::ivec3 n = scene_.grid.size;
  in.flags.resize(cellCount(n));
  for (int c = 0; c < int(in.flags.size()); ++c) {
    const glm::dvec3 p = glm::dvec3(cellOf(c, n)) + 0.5;
    CellFlags& f = in.flags[c];
    f.previousObstacle = previous[c].obstacle;
    for (size_t o = 0; o < centres.size() && !f.solid(); ++o)
      if (shapeTest(scene_.obstacles[o], centres[o], p).inside) f.obstacle = int(o);
    for (size_t i = 0; i < scene_.inlets.size() && f.inlet < 0 && !f.solid(); ++i) {
      const scene::Inlet& inlet = scene_.inlets[i];
      if (time >= inlet.start && time < inlet.stop && insideInlet(inlet, p)) f.inlet = int(i);
    }
  }
  return in;
}

void CpuSimulation::advance(int steps) {
  std::vector<glm::dvec2> inletSmoke;
  for (const scene::Inlet& inlet : scene_.inlets) inletSmoke.emplace_back(inlet.density, inlet.temperature);
  const double decay = std::exp(-double(scene_.smoke.dissipation));
  for (int s = 0; s < steps; ++s, ++step_) {
    const CpuStepInputs in = inputsAt(step_, flags_);
    lbm_.step(in, smoke_);
    applySmokeSources(smokeSettings_, in.flags, inletSmoke, decay, smoke_);
    std::vector<bool> solid(in.flags.size());
    std::vector<glm::dvec3> velocity(in.flags.size());
    for (size_t c = 0; c < solid.size(); ++c) {
      solid[c] = in.flags[c].solid();
      velocity[c] = glm::dvec3(lbm_.macro()[c]);
    }
    transportSmoke(smokeSettings_, solid, velocity, smoke_);
    flags_ = in.flags;
  }
}

}  // namespace sixway::test
