#include "cpu_lbm.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sixway::test {
namespace {

using d3q19::kQ;
using scene::BoundaryType;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

BoundaryType faceCrossed(const CpuLbmSettings& s, glm::ivec3 source, int axis) {
  return s.faces[2 * axis + (source[axis] < 0 ? 0 : 1)];
}

bool isWall(BoundaryType t) {
  return t == BoundaryType::NoSlip || t == BoundaryType::FreeSlip;
}

d3q19::Populations equilibria(double rho, glm::dvec3 u) {
  d3q19::Populations f{};
  for (int i = 0; i < kQ; ++i) f[i] = d3q19::equilibrium(i, rho, u);
  return f;
}

// The population that a wall moving at u_w sends back along c_i: f*_ī + 2 w_i ρ c_i·u_w / c_s².
double movingBounceBack(int i, double postOpposite, double rho, glm::dvec3 wall) {
  return postOpposite +
         2 * d3q19::weight(i) * rho * glm::dot(glm::dvec3(d3q19::velocity(i)), wall) / d3q19::kCs2;
}

glm::ivec3 wrapPeriodic(glm::ivec3 p, glm::ivec3 size, const std::array<scene::BoundaryType, 6>& faces) {
  for (int a = 0; a < 3; ++a)
    if (faces[2 * a] == BoundaryType::Periodic) p[a] = ((p[a] % size[a]) + size[a]) % size[a];
  return p;
}

// Where the link from x (outside obstacle o) to x − c (inside it) enters the obstacle, as a fraction of the
// link: bisection of the inside test, to far below float rounding (the shapes are convex: one crossing).
// ½ when x lies inside too (an obstacle cut by a periodic face is not wrapped around it).
double wallFraction(const CpuStepInputs& in, int o, glm::dvec3 x, glm::dvec3 c) {
  if (in.insideObstacle(o, x) || !in.insideObstacle(o, x - c)) return 0.5;
  double outside = 0, inside = 1;
  for (int k = 0; k < 60; ++k) {
    const double t = 0.5 * (outside + inside);
    (in.insideObstacle(o, x - t * c) ? inside : outside) = t;
  }
  return std::clamp(inside, 1e-3, 1.0);
}

// The population f_i that the wall in cell `from` = p − c_i (wrapped) sends back to the fluid cell p, by
// the rule of the settings (cpu_lbm.h). `post` and `macro`: the state the step streams from.
double bounceBack(const CpuLbmSettings& s, const std::vector<d3q19::Populations>& post,
                  const std::vector<glm::dvec4>& macro, const CpuStepInputs& in, glm::ivec3 p, int i,
                  int from) {
  const int cell = cellIndex(p, s.size);
  const int o = in.flags[from].wall();
  const glm::dvec3 wall = in.obstacleVelocity[o];
  const double rho = macro[cell].w;
  const double toWall = post[cell][d3q19::opposite(i)];
  const double halfWay = movingBounceBack(i, toWall, rho, wall);
  if (!s.interpolatedBounceBack || !in.flags[from].solid()) return halfWay;
  const glm::dvec3 c(d3q19::velocity(i));
  // The fluid cell's centre on the wall cell's side of a periodic face.
  const double q = wallFraction(in, o, glm::dvec3(cellOf(from, s.size)) + c + 0.5, c);
  if (q >= 0.5) return (halfWay + (2 * q - 1) * post[cell][i]) / (2 * q);
  const glm::ivec3 beyond = wrapPeriodic(p + d3q19::velocity(i), s.size, s.faces);
  if (!insideGrid(beyond, s.size) || in.flags[cellIndex(beyond, s.size)].wall() >= 0) return halfWay;
  const double farther = post[cellIndex(beyond, s.size)][d3q19::opposite(i)];
  return movingBounceBack(i, 2 * q * toWall + (1 - 2 * q) * farther, rho, wall);
}

}  // namespace

int cellIndex(glm::ivec3 p, glm::ivec3 size) {
  return p.x + size.x * (p.y + size.y * p.z);
}

glm::ivec3 cellOf(int index, glm::ivec3 size) {
  return {index % size.x, (index / size.x) % size.y, index / (size.x * size.y)};
}

bool insideGrid(glm::ivec3 p, glm::ivec3 size) {
  return glm::all(glm::greaterThanEqual(p, glm::ivec3(0))) && glm::all(glm::lessThan(p, size));
}

CpuLbm::CpuLbm(const CpuLbmSettings& settings, std::vector<glm::dvec4> macro)
    : settings_(settings), macro_(std::move(macro)) {
  const glm::ivec3 n = settings.size;
  if (macro_.size() != size_t(n.x) * n.y * n.z)
    throw std::invalid_argument("CpuLbm: one macro state per cell");
  for (const glm::dvec4& m : macro_) post_.push_back(equilibria(m.w, glm::dvec3(m)));
}

double CpuLbm::fromOutside(int i, glm::ivec3 p, glm::ivec3 source, const CpuStepInputs& inputs) const {
  const CpuLbmSettings& s = settings_;
  const int cell = cellIndex(p, s.size);
  const double bounceBack = post_[cell][d3q19::opposite(i)];
  int crossed = 0, lastAxis = 0;
  bool wall = false, inflow = false;
  for (int a = 0; a < 3; ++a) {
    if (source[a] >= 0 && source[a] < s.size[a]) continue;
    ++crossed;
    lastAxis = a;
    wall = wall || isWall(faceCrossed(s, source, a));
    inflow = inflow || faceCrossed(s, source, a) == BoundaryType::Inflow;
  }
  if (wall) {
    if (crossed > 1 || faceCrossed(s, source, lastAxis) != BoundaryType::FreeSlip) return bounceBack;
    // Specular reflection: the population left `from` with its normal component pointing at the wall.
    glm::ivec3 from = source, mirrored = d3q19::velocity(i);
    from[lastAxis] = p[lastAxis];
    mirrored[lastAxis] = -mirrored[lastAxis];
    const int fromCell = cellIndex(from, s.size);
    if (inputs.flags[fromCell].wall() >= 0) return bounceBack;
    for (int j = 0; j < kQ; ++j)
      if (d3q19::velocity(j) == mirrored) return post_[fromCell][j];
    throw std::logic_error("no mirrored velocity");
  }
  if (inflow) {
    glm::dvec3 u = s.wind;
    for (int b = 0; s.parabolicInflow && b < 3; ++b) {
      if (b == lastAxis || s.faces[2 * b] != BoundaryType::NoSlip ||
          s.faces[2 * b + 1] != BoundaryType::NoSlip)
        continue;
      const double across = (p[b] + 0.5) / s.size[b];
      u *= 4 * across * (1 - across);
    }
    return movingBounceBack(i, bounceBack, macro_[cell].w, u);
  }
  // Outflow: ambient pressure, the cell's velocity without its component back into the domain.
  glm::dvec3 u(macro_[cell]);
  for (int a = 0; a < 3; ++a) {
    if (source[a] < 0) u[a] = std::min(u[a], 0.0);
    if (source[a] >= s.size[a]) u[a] = std::max(u[a], 0.0);
  }
  return d3q19::equilibrium(i, 1.0, u);
}

d3q19::Populations CpuLbm::gather(glm::ivec3 p, const CpuStepInputs& inputs) const {
  const CpuLbmSettings& s = settings_;
  const int cell = cellIndex(p, s.size);
  if (inputs.flags[cell].uncovered()) return equilibria(1.0, glm::dvec3(macro_[cell]));
  d3q19::Populations f{};
  for (int i = 0; i < kQ; ++i) {
    const glm::ivec3 source = wrapPeriodic(p - d3q19::velocity(i), s.size, s.faces);
    if (!insideGrid(source, s.size)) {
      f[i] = fromOutside(i, p, source, inputs);
      continue;
    }
    const int from = cellIndex(source, s.size);
    f[i] = inputs.flags[from].wall() >= 0 ? bounceBack(s, post_, macro_, inputs, p, i, from) : post_[from][i];
  }
  return f;
}

glm::dvec3 CpuLbm::acceleration(glm::ivec3 p, const std::vector<glm::dvec2>& smoke) const {
  const CpuLbmSettings& s = settings_;
  const int r = s.smokeUpres;
  glm::dvec2 mean(0);
  for (int z = 0; z < r; ++z)
    for (int y = 0; y < r; ++y)
      for (int x = 0; x < r; ++x) mean += smoke[cellIndex(p * r + glm::ivec3(x, y, z), s.size * r)];
  mean /= double(r * r * r);
  return (s.buoyancyTemperature * mean.y + s.buoyancyDensity * mean.x) * s.up + s.bodyAcceleration;
}

void CpuLbm::step(const CpuStepInputs& inputs, const std::vector<glm::dvec2>& smoke) {
  const glm::ivec3 n = settings_.size;
  std::vector<glm::dvec4> macro(macro_.size());
  std::vector<d3q19::Populations> post(post_.size());
  for (int cell = 0; cell < int(macro_.size()); ++cell) {
    const CellFlags& flags = inputs.flags[cell];
    if (flags.solid()) {
      macro[cell] = glm::dvec4(inputs.obstacleVelocity[flags.obstacle], 1.0);
      post[cell].fill(kNaN);
      continue;
    }
    const glm::ivec3 p = cellOf(cell, n);
    const d3q19::Populations f = gather(p, inputs);
    double rho = 0;
    for (double value : f) rho += value;
    const glm::dvec3 force = rho * acceleration(p, smoke);
    const d3q19::Moments m = d3q19::moments(f, force);
    if (flags.inlet >= 0) {
      const glm::dvec3 u = inputs.inletVelocity[flags.inlet];
      post[cell] = equilibria(m.rho, u);
      macro[cell] = glm::dvec4(u, m.rho);
      continue;
    }
    post[cell] = d3q19::collide(m, d3q19::effectiveTau(settings_.tau, settings_.smagorinsky, m), force);
    macro[cell] = glm::dvec4(m.u, m.rho);
  }
  macro_ = std::move(macro);
  post_ = std::move(post);
}

LinkForces momentumExchange(const CpuLbmSettings& settings, const std::vector<d3q19::Populations>& post,
                            const std::vector<glm::dvec4>& macro, const CpuStepInputs& inputs) {
  LinkForces out;
  out.force.assign(inputs.obstacleVelocity.size(), glm::dvec3(0));
  out.magnitude = out.force;
  for (int cell = 0; cell < int(post.size()); ++cell) {
    const CellFlags& here = inputs.flags[cell];
    // A cell the obstacle covers now hands its fluid momentum to it; one it uncovers restarts at
    // ρ = 1 with the velocity it carried as a wall, taken from the obstacle (Wen et al.'s refilling).
    if (here.solid() && here.previousObstacle < 0) {
      const glm::dvec3 momentum = macro[cell].w * glm::dvec3(macro[cell]);
      out.force[here.obstacle] += momentum;
      out.magnitude[here.obstacle] += glm::abs(momentum);
    }
    if (here.uncovered()) {
      out.force[here.previousObstacle] -= glm::dvec3(macro[cell]);
      out.magnitude[here.previousObstacle] += glm::abs(glm::dvec3(macro[cell]));
    }
    if (here.solid() || here.uncovered()) continue;  // no bounce-back happens there
    const glm::ivec3 p = cellOf(cell, settings.size);
    for (int i = 1; i < d3q19::kQ; ++i) {
      const glm::ivec3 source = wrapPeriodic(p - d3q19::velocity(i), settings.size, settings.faces);
      if (!insideGrid(source, settings.size)) continue;
      const int from = cellIndex(source, settings.size);
      const int o = inputs.flags[from].wall();
      if (o < 0) continue;
      const glm::dvec3 wall = inputs.obstacleVelocity[o];
      const glm::dvec3 c(d3q19::velocity(i));
      const double toWall = post[cell][d3q19::opposite(i)];
      const double back = bounceBack(settings, post, macro, inputs, p, i, from);
      out.force[o] += (-c - wall) * toWall - (c - wall) * back;
      out.magnitude[o] += glm::abs(-c - wall) * std::abs(toWall) + glm::abs(c - wall) * std::abs(back);
    }
  }
  return out;
}

}  // namespace sixway::test
