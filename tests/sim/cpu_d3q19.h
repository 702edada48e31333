#pragma once
// CPU oracle: the D3Q19 velocity set and the cell-local part of a lattice Boltzmann step, in double
// precision, written from the equations (lattice units, c_s² = 1/3):
//   equilibrium      f_i^eq = w_i ρ (1 + c_i·u/c_s² + (c_i·u)²/(2c_s⁴) − u²/(2c_s²))
//   Guo forcing      u = (Σ c_i f_i + F/2)/ρ,  S_i = w_i [(c_i − u)/c_s² + (c_i·u) c_i/c_s⁴]·F
//   regularized BGK  f − f^eq projected on the Hermite polynomials of order 1 and 2 (Latt & Chopard
//                    2006): j^neq = Σ c_i f_i − ρ u (= −F/2), Π^neq = Σ c_i c_i f_i − ρ c_s² I − ρ u u,
//                    f_i^neq = w_i [c_i·j^neq / c_s² + (c_i c_i − c_s² I) : Π^neq / (2c_s⁴)]
//   collision        f_i* = f_i^eq + (1 − 1/τ) f_i^neq + (1 − 1/(2τ)) S_i
//                    (so Σ c_i f_i* = Σ c_i f_i + F exactly, and the second moment is that of Guo-BGK)
//   Smagorinsky      τ = τ₀ + 3 ν_t, ν_t = C² |S|, |S| = √(2 S:S); with Guo forcing the Chapman–Enskog
//                    strain is S = −(Π^neq + (F u + u F)/2) / (2ρ c_s² τ); solved for τ
// Only the ordering of the velocities is shared with the shaders (shaders/common/lbm_d3q19.glsl):
// the GPU lattice stores population i at that index.
#include <array>
#include <glm/glm.hpp>

namespace sixway::test::d3q19 {

inline constexpr int kQ = 19;
inline constexpr double kCs2 = 1.0 / 3.0;

using Populations = std::array<double, kQ>;

const glm::ivec3& velocity(int i);
double weight(int i);
// The index of −c_i.
int opposite(int i);

double equilibrium(int i, double rho, glm::dvec3 u);

struct Moments {
  double rho = 0;
  glm::dvec3 u{0};           // with the half-force shift
  glm::dvec3 jNeq{0};        // Σ c f − ρ u
  glm::dmat3 piNeq{0};       // Σ c c f − ρ c_s² I − ρ u u
  glm::dmat3 strainFlux{0};  // Π^neq + (F u + u F)/2 = −2ρ c_s² τ S
};
Moments moments(const Populations& f, glm::dvec3 force);

// τ including the Smagorinsky eddy viscosity (τ₀ when smagorinsky = 0).
double effectiveTau(double tau0, double smagorinsky, const Moments& m);

Populations collide(const Moments& m, double tau, glm::dvec3 force);

}  // namespace sixway::test::d3q19
