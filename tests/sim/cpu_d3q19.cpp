#include "cpu_d3q19.h"

#include <cmath>
#include <stdexcept>

namespace sixway::test::d3q19 {
namespace {

// Rest, the six axis neighbours, then the twelve edge neighbours, each followed by its opposite.
constexpr std::array<glm::ivec3, kQ> kVelocities = {{
    {0, 0, 0},  {1, 0, 0},   {-1, 0, 0}, {0, 1, 0},   {0, -1, 0}, {0, 0, 1},   {0, 0, -1},
    {1, 1, 0},  {-1, -1, 0}, {1, 0, 1},  {-1, 0, -1}, {0, 1, 1},  {0, -1, -1}, {1, -1, 0},
    {-1, 1, 0}, {1, 0, -1},  {-1, 0, 1}, {0, 1, -1},  {0, -1, 1},
}};

std::array<int, kQ> oppositeTable() {
  std::array<int, kQ> table{};
  for (int i = 0; i < kQ; ++i) {
    table[i] = -1;
    for (int j = 0; j < kQ; ++j)
      if (kVelocities[j] == -kVelocities[i]) table[i] = j;
    if (table[i] < 0) throw std::logic_error("D3Q19 velocity set without an opposite");
  }
  return table;
}

glm::dvec3 cf(int i) {
  return glm::dvec3(kVelocities[i]);
}

}  // namespace

const glm::ivec3& velocity(int i) {
  return kVelocities[i];
}

double weight(int i) {
  const glm::ivec3 c = kVelocities[i];
  const int speedSquared = c.x * c.x + c.y * c.y + c.z * c.z;
  return speedSquared == 0 ? 1.0 / 3.0 : speedSquared == 1 ? 1.0 / 18.0 : 1.0 / 36.0;
}

int opposite(int i) {
  static const std::array<int, kQ> table = oppositeTable();
  return table[i];
}

double equilibrium(int i, double rho, glm::dvec3 u) {
  const double cu = glm::dot(cf(i), u);
  return weight(i) * rho * (1 + cu / kCs2 + cu * cu / (2 * kCs2 * kCs2) - glm::dot(u, u) / (2 * kCs2));
}

Moments moments(const Populations& f, glm::dvec3 force) {
  Moments m;
  glm::dvec3 momentum(0);
  glm::dmat3 flux(0);
  for (int i = 0; i < kQ; ++i) {
    m.rho += f[i];
    momentum += f[i] * cf(i);
    flux += f[i] * glm::outerProduct(cf(i), cf(i));
  }
  m.u = (momentum + 0.5 * force) / m.rho;
  m.jNeq = momentum - m.rho * m.u;
  m.piNeq = flux - m.rho * kCs2 * glm::dmat3(1.0) - m.rho * glm::outerProduct(m.u, m.u);
  m.strainFlux = m.piNeq + 0.5 * (glm::outerProduct(force, m.u) + glm::outerProduct(m.u, force));
  return m;
}

double effectiveTau(double tau0, double smagorinsky, const Moments& m) {
  double norm2 = 0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) norm2 += m.strainFlux[a][b] * m.strainFlux[a][b];
  // τ = τ₀ + 3C²|S| with |S| = √2 |strain flux| / (2ρc_s²τ): τ² − τ₀τ − k = 0.
  const double k = 3 * smagorinsky * smagorinsky * std::sqrt(2.0) * std::sqrt(norm2) / (2 * m.rho * kCs2);
  return 0.5 * (tau0 + std::sqrt(tau0 * tau0 + 4 * k));
}

Populations collide(const Moments& m, double tau, glm::dvec3 force) {
  Populations out{};
  for (int i = 0; i < kQ; ++i) {
    const glm::dvec3 c = cf(i);
    double qPi = 0;  // (c c − c_s² I) : Π^neq
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) qPi += (c[a] * c[b] - (a == b ? kCs2 : 0.0)) * m.piNeq[a][b];
    const double nonEquilibrium = weight(i) * (glm::dot(c, m.jNeq) / kCs2 + qPi / (2 * kCs2 * kCs2));
    const double source =
        weight(i) * glm::dot((c - m.u) / kCs2 + glm::dot(c, m.u) * c / (kCs2 * kCs2), force);
    out[i] = equilibrium(i, m.rho, m.u) + (1 - 1 / tau) * nonEquilibrium + (1 - 1 / (2 * tau)) * source;
  }
  return out;
}

}  // namespace sixway::test::d3q19
