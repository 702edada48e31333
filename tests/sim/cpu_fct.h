#pragma once
// CPU oracle: smoke sources and flux-corrected transport (Zalesak 1979), in double precision, on the
// smoke grid (upres times finer than the lattice, cells x fastest). One substep moves the smoke by the
// lattice velocity for 1/upres of a lattice step, so the velocity in lattice cells per step is also the
// Courant number in smoke cells per substep. Per face, with u the normal velocity there:
//   low order   F_L = u q_upwind                                   (donor cell)
//   high order  F_H = u (q_l + q_r)/2 − u² (q_r − q_l)/2           (Lax–Wendroff)
//   q_td = q + Σ (F_L in − F_L out);  A = F_H − F_L;  the limiter C ∈ [0, 1] of each face keeps
//   q_td + Σ C A within the extrema of q and q_td over the cell and its face neighbours.
// The face velocity is the trilinear interpolation of the lattice cell-centre velocities at the face
// centre (wrapped on periodic axes, held constant beyond the outer centres otherwise); with upres 1 that
// is the mean of the two cells. Walls and obstacle faces pass nothing; an open face (outflow, inflow)
// lets smoke leave with the boundary cell's own velocity and lets nothing in.
#include <array>
#include <glm/glm.hpp>
#include <vector>

#include "cpu_lbm.h"
#include "scene/scene.h"

namespace sixway::test {

struct CpuSmokeSettings {
  glm::ivec3 lattice{0};
  int upres = 1;
  std::array<scene::BoundaryType, 6> faces{};
  glm::ivec3 smokeSize() const { return lattice * upres; }
};

// `upres` substeps of transport of each smoke component by the lattice velocity; `solid` per lattice cell.
void transportSmoke(const CpuSmokeSettings& s, const std::vector<bool>& solid,
                    const std::vector<glm::dvec3>& velocity, std::vector<glm::dvec2>& smoke);

// Smoke cells of an inlet take its (density, temperature); elsewhere the smoke decays by `decay`.
void applySmokeSources(const CpuSmokeSettings& s, const std::vector<CellFlags>& flags,
                       const std::vector<glm::dvec2>& inletSmoke, double decay,
                       std::vector<glm::dvec2>& smoke);

}  // namespace sixway::test
