#include "cpu_fct.h"

#include <algorithm>
#include <cmath>

namespace sixway::test {
namespace {

using scene::BoundaryType;

// The lattice velocity (cells per step) at x in lattice coordinates (cell centres at integer + 0.5).
glm::dvec3 sampleVelocity(const CpuSmokeSettings& s, const std::vector<glm::dvec3>& velocity, glm::dvec3 x) {
  glm::ivec3 i0, i1;
  glm::dvec3 t;
  for (int a = 0; a < 3; ++a) {
    const int n = s.lattice[a];
    double g = x[a] - 0.5;
    if (s.faces[2 * a] == BoundaryType::Periodic) {
      const double base = std::floor(g);
      t[a] = g - base;
      i0[a] = ((int(base) % n) + n) % n;
      i1[a] = (i0[a] + 1) % n;
    } else {
      g = std::clamp(g, 0.0, double(n - 1));
      i0[a] = std::min(int(std::floor(g)), std::max(n - 2, 0));
      i1[a] = std::min(i0[a] + 1, n - 1);
      t[a] = g - i0[a];
    }
  }
  glm::dvec3 u(0);
  for (int corner = 0; corner < 8; ++corner) {
    glm::ivec3 p;
    double w = 1;
    for (int a = 0; a < 3; ++a) {
      const bool high = (corner >> a) & 1;
      p[a] = high ? i1[a] : i0[a];
      w *= high ? t[a] : 1 - t[a];
    }
    u += w * velocity[cellIndex(p, s.lattice)];
  }
  return u;
}

struct FaceFlux {
  double low = 0, antidiffusive = 0;
};

class FctSubstep {
 public:
  FctSubstep(const CpuSmokeSettings& s, const std::vector<bool>& solid,
             const std::vector<glm::dvec3>& velocity, const std::vector<double>& q)
      : s_(s), n_(s.smokeSize()), solid_(solid), velocity_(velocity), q_(q) {}

  std::vector<double> run() const {
    const int cells = int(q_.size());
    std::vector<double> lowOrder(cells);
    for (int c = 0; c < cells; ++c) {
      const glm::ivec3 p = cellOf(c, n_);
      lowOrder[c] = q_[c];
      for (int a = 0; a < 3; ++a) lowOrder[c] += face(p, a).low - face(p + unit(a), a).low;
    }
    std::vector<double> rPlus(cells), rMinus(cells);
    for (int c = 0; c < cells; ++c) limiter(c, lowOrder, rPlus[c], rMinus[c]);
    std::vector<double> out(cells);
    for (int c = 0; c < cells; ++c) {
      const glm::ivec3 p = cellOf(c, n_);
      out[c] = lowOrder[c];
      for (int a = 0; a < 3; ++a) {
        out[c] += limited(p, a, rPlus, rMinus);
        out[c] -= limited(p + unit(a), a, rPlus, rMinus);
      }
    }
    return out;
  }

 private:
  static glm::ivec3 unit(int a) {
    glm::ivec3 e(0);
    e[a] = 1;
    return e;
  }
  bool periodic(int a) const { return s_.faces[2 * a] == BoundaryType::Periodic; }
  bool solidAt(glm::ivec3 p) const { return solid_[cellIndex(p / s_.upres, s_.lattice)]; }
  // The smoke cell across the face of p along a on `side` (−1, +1); false outside a non-periodic domain.
  bool neighbour(glm::ivec3 p, int a, int side, glm::ivec3& out) const {
    out = p;
    out[a] += side;
    if (out[a] >= 0 && out[a] < n_[a]) return true;
    if (!periodic(a)) return false;
    out[a] = (out[a] + n_[a]) % n_[a];
    return true;
  }

  // The flux through the lower face of smoke cell p along a (p[a] may be n[a]: the upper boundary).
  FaceFlux face(glm::ivec3 p, int a) const {
    const double upres = s_.upres;
    const bool lower = p[a] == 0, upper = p[a] == n_[a];
    if ((lower || upper) && !periodic(a)) {
      const BoundaryType type = s_.faces[2 * a + (upper ? 1 : 0)];
      if (type == BoundaryType::NoSlip || type == BoundaryType::FreeSlip) return {};
      glm::ivec3 inside = p;
      if (upper) inside[a] -= 1;
      if (solidAt(inside)) return {};
      const double u = sampleVelocity(s_, velocity_, (glm::dvec3(inside) + 0.5) / upres)[a];
      const bool leaving = upper ? u > 0 : u < 0;
      return {leaving ? u * q_[cellIndex(inside, n_)] : 0.0, 0.0};
    }
    glm::ivec3 left = p, right = p;
    left[a] = (p[a] - 1 + n_[a]) % n_[a];
    right[a] = p[a] % n_[a];
    if (solidAt(left) || solidAt(right)) return {};
    glm::dvec3 x = (glm::dvec3(p) + 0.5) / upres;
    x[a] = p[a] / upres;
    const double u = sampleVelocity(s_, velocity_, x)[a];
    const double ql = q_[cellIndex(left, n_)], qr = q_[cellIndex(right, n_)];
    const double low = u > 0 ? u * ql : u * qr;
    const double high = u * 0.5 * (ql + qr) - 0.5 * u * u * (qr - ql);
    return {low, high - low};
  }

  // Zalesak's R+ and R− of cell c: the fraction of the antidiffusive inflow (outflow) that keeps it
  // at most (at least) the largest (smallest) of q and q_td over the cell and its fluid neighbours.
  void limiter(int c, const std::vector<double>& lowOrder, double& rPlus, double& rMinus) const {
    const glm::ivec3 p = cellOf(c, n_);
    double highest = std::max(q_[c], lowOrder[c]), lowest = std::min(q_[c], lowOrder[c]);
    double in = 0, out = 0;
    for (int a = 0; a < 3; ++a) {
      for (int side : {-1, 1}) {
        glm::ivec3 n;
        if (!neighbour(p, a, side, n) || solidAt(n)) continue;
        const int ni = cellIndex(n, n_);
        highest = std::max({highest, q_[ni], lowOrder[ni]});
        lowest = std::min({lowest, q_[ni], lowOrder[ni]});
      }
      const double intoLower = face(p, a).antidiffusive, intoUpper = -face(p + unit(a), a).antidiffusive;
      for (double into : {intoLower, intoUpper}) {
        in += std::max(into, 0.0);
        out += std::max(-into, 0.0);
      }
    }
    rPlus = in > 0 ? std::min(1.0, (highest - lowOrder[c]) / in) : 0.0;
    rMinus = out > 0 ? std::min(1.0, (lowOrder[c] - lowest) / out) : 0.0;
  }

  // C·A of the lower face of p along a (Zalesak 1979, eq. 13).
  double limited(glm::ivec3 p, int a, const std::vector<double>& rPlus,
                 const std::vector<double>& rMinus) const {
    const double flux = face(p, a).antidiffusive;
    if (flux == 0) return 0;
    glm::ivec3 left = p, right = p;
    left[a] = (p[a] - 1 + n_[a]) % n_[a];
    right[a] = p[a] % n_[a];
    const int l = cellIndex(left, n_), r = cellIndex(right, n_);
    return flux * (flux > 0 ? std::min(rPlus[r], rMinus[l]) : std::min(rPlus[l], rMinus[r]));
  }

  const CpuSmokeSettings& s_;
  glm::ivec3 n_;
  const std::vector<bool>& solid_;
  const std::vector<glm::dvec3>& velocity_;
  const std::vector<double>& q_;
};

}  // namespace

void transportSmoke(const CpuSmokeSettings& s, const std::vector<bool>& solid,
                    const std::vector<glm::dvec3>& velocity, std::vector<glm::dvec2>& smoke) {
  for (int substep = 0; substep < s.upres; ++substep)
    for (int component = 0; component < 2; ++component) {
      std::vector<double> q(smoke.size());
      for (size_t c = 0; c < q.size(); ++c) q[c] = smoke[c][component];
      const std::vector<double> moved = FctSubstep(s, solid, velocity, q).run();
      for (size_t c = 0; c < q.size(); ++c) smoke[c][component] = moved[c];
    }
}

void applySmokeSources(const CpuSmokeSettings& s, const std::vector<CellFlags>& flags,
                       const std::vector<glm::dvec2>& inletSmoke, double decay,
                       std::vector<glm::dvec2>& smoke) {
  const glm::ivec3 n = s.smokeSize();
  for (int c = 0; c < int(smoke.size()); ++c) {
    const int inlet = flags[cellIndex(cellOf(c, n) / s.upres, s.lattice)].inlet;
    smoke[c] = inlet >= 0 ? inletSmoke[inlet] : smoke[c] * decay;
  }
}

}  // namespace sixway::test
