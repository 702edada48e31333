#pragma once
// CPU oracle: one lattice Boltzmann step on a whole grid (pull streaming with the boundary conditions,
// then the collision of cpu_d3q19.h), and the momentum-exchange force on obstacles. Double precision,
// cells x fastest. Conventions (docs/scene-format.md and the comments in shaders/sim/lbm_step.comp):
//   - walls sit half-way between cells; no_slip: bounce-back f_i = f*_ī; free_slip: specular reflection
//     (the population left the tangential neighbour with its normal component flipped); an edge or corner
//     link that crosses a wall bounces back;
//   - obstacles: half-way bounce-back from a wall moving at u_w, f_i = f*_ī + 2 w_i ρ_prev c_i·u_w / c_s²
//     (Ladd 1994); solid cells carry (u_w, 1) as their macro state;
//   - or, with interpolatedBounceBack, the linear interpolated bounce-back of Bouzidi, Firdaouss & Lallemand
//     (2001), the wall at the fraction q of the link x → x − c_i where it enters the obstacle (bisection of
//     the inside test), q clamped to [1e-3, 1], m = 2 w_i ρ_prev c_i·u_w / c_s²:
//       q < ½: f_i = 2q f*_ī(x) + (1 − 2q) f*_ī(x + c_i) + m;
//       q ≥ ½: f_i = [f*_ī(x) + (2q − 1) f*_i(x) + m] / (2q);
//     half-way when x + c_i is not a fluid cell (q < ½), the wall cell was uncovered this step, or x itself
//     lies inside the obstacle (cut by a periodic face, whose image across it is not an obstacle);
//   - inflow faces: the same moving-wall bounce-back with u_w = wind · 4s(1 − s) per no-slip channel axis
//     when parabolic; outflow faces: f_i = f_i^eq(1, u_prev); at edges and corners a wall wins over
//     inflow, inflow over outflow;
//   - a cell uncovered by a moving obstacle starts from f^eq(1, u_prev) (u_prev: the wall's velocity);
//     a neighbour streaming from it still sees the wall of the obstacle that covered it (its populations
//     did not exist a step ago) and gets that obstacle's moving-wall bounce-back;
//   - velocity inlets: the populations become f^eq(ρ, u_inlet);
//   - force ρ a per cell, a = (b_T T + b_ρ D) up + body, T and D averaged over the cell's smoke cells.
#include <array>
#include <functional>
#include <glm/glm.hpp>
#include <vector>

#include "cpu_d3q19.h"
#include "scene/scene.h"

namespace sixway::test {

// What obstacles and inlets make of one lattice cell at one step.
struct CellFlags {
  int obstacle = -1;          // the covering obstacle, −1: fluid
  int previousObstacle = -1;  // the one covering it a step before
  int inlet = -1;             // the velocity inlet forcing the cell, −1: none
  bool solid() const { return obstacle >= 0; }
  bool uncovered() const { return obstacle < 0 && previousObstacle >= 0; }
  // The wall a population streaming out of this cell comes from: the obstacle covering it, or for an
  // uncovered cell (whose populations the step only now refills) the one that covered it; −1: none.
  int wall() const { return solid() ? obstacle : previousObstacle; }
};

struct CpuLbmSettings {
  glm::ivec3 size{0};
  std::array<scene::BoundaryType, 6> faces{};  // x−, x+, y−, y+, z−, z+
  double tau = 0.6;
  double smagorinsky = 0;
  int smokeUpres = 1;
  double buoyancyTemperature = 0, buoyancyDensity = 0;  // lattice acceleration per unit
  glm::dvec3 up{0, 1, 0};
  glm::dvec3 bodyAcceleration{0};
  glm::dvec3 wind{0};
  bool parabolicInflow = false;
  bool interpolatedBounceBack = false;
};

// The moving parts at one step, lattice units.
struct CpuStepInputs {
  std::vector<CellFlags> flags;
  std::vector<glm::dvec3> obstacleVelocity;
  std::vector<glm::dvec3> inletVelocity;
  // Whether a point (lattice coordinates) lies inside obstacle o at this step; for interpolated bounce-back.
  std::function<bool(int o, glm::dvec3 p)> insideObstacle;
};

class CpuLbm {
 public:
  // Populations at the equilibrium of `macro` (u, ρ per cell).
  CpuLbm(const CpuLbmSettings& settings, std::vector<glm::dvec4> macro);

  // One step; `smoke` holds (density, temperature) per smoke cell.
  void step(const CpuStepInputs& inputs, const std::vector<glm::dvec2>& smoke);

  const CpuLbmSettings& settings() const { return settings_; }
  const std::vector<glm::dvec4>& macro() const { return macro_; }

 private:
  d3q19::Populations gather(glm::ivec3 p, const CpuStepInputs& inputs) const;
  double fromOutside(int i, glm::ivec3 p, glm::ivec3 source, const CpuStepInputs& inputs) const;
  glm::dvec3 acceleration(glm::ivec3 p, const std::vector<glm::dvec2>& smoke) const;

  CpuLbmSettings settings_;
  std::vector<glm::dvec4> macro_;
  std::vector<d3q19::Populations> post_;  // what the next step streams from; NaN in solid cells (never read)
};

// Cell index, x fastest, and back; whether p lies in the grid.
int cellIndex(glm::ivec3 p, glm::ivec3 size);
glm::ivec3 cellOf(int index, glm::ivec3 size);
bool insideGrid(glm::ivec3 p, glm::ivec3 size);

// The force of the fluid on each obstacle by momentum exchange over the links that the coming step
// bounces back (Galilean-invariant form, Wen et al. 2014): per link from a fluid cell x (not one just
// uncovered) along c_i to a wall cell (CellFlags::wall), F += (c_ī − u_w) f*_ī(x) − (c_i − u_w) f_i(x)
// with f_i(x) the bounced-back population; plus the momentum of the cells a moving obstacle covers
// (their ρu, to the obstacle) and uncovers (the refill's ρ₀u_w, from it). f_i(x) follows the bounce-back
// rule of `settings`.
// `post` is the state the step streams from, `macro` the macro state before it, `flags` the step's.
struct LinkForces {
  std::vector<glm::dvec3> force;
  std::vector<glm::dvec3> magnitude;  // Σ |term| per component, for rounding bounds
};
LinkForces momentumExchange(const CpuLbmSettings& settings, const std::vector<d3q19::Populations>& post,
                            const std::vector<glm::dvec4>& macro, const CpuStepInputs& inputs);

}  // namespace sixway::test
