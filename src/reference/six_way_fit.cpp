#include "reference/six_way_fit.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace sixway::reference {
namespace {

// The inverse of the k × k symmetric positive-definite matrix `a` (row-major), by Gauss–Jordan elimination;
// false when a pivot is not clearly positive (a channel the directions cannot tell from the others).
bool invert(std::vector<double> a, int k, std::vector<double>& inverse) {
  inverse.assign(size_t(k) * k, 0.0);
  for (int i = 0; i < k; ++i) inverse[size_t(i) * k + i] = 1.0;
  double largest = 0.0;
  for (int i = 0; i < k; ++i) largest = std::max(largest, a[size_t(i) * k + i]);
  for (int col = 0; col < k; ++col) {
    const double pivot = a[size_t(col) * k + col];
    if (!(pivot > 1e-9 * largest)) return false;
    for (int j = 0; j < k; ++j) {
      a[size_t(col) * k + j] /= pivot;
      inverse[size_t(col) * k + j] /= pivot;
    }
    for (int row = 0; row < k; ++row) {
      const double f = a[size_t(row) * k + col];
      if (row == col || f == 0.0) continue;
      for (int j = 0; j < k; ++j) {
        a[size_t(row) * k + j] -= f * a[size_t(col) * k + j];
        inverse[size_t(row) * k + j] -= f * inverse[size_t(col) * k + j];
      }
    }
  }
  return true;
}

}  // namespace

std::array<float, 6> sixWayWeights(glm::vec3 d) {
  std::array<float, 6> w{};
  for (int axis = 0; axis < 3; ++axis) w[2 * axis + (d[axis] >= 0.0f ? 0 : 1)] = d[axis] * d[axis];
  return w;
}

std::vector<glm::vec3> sphereDirections(int count) {
  if (count < 1) throw std::invalid_argument("sphereDirections: the count must be at least 1");
  const double goldenAngle = std::numbers::pi * (3.0 - std::sqrt(5.0));
  std::vector<glm::vec3> directions;
  for (int k = 0; k < count; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / count, r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = goldenAngle * k;
    directions.emplace_back(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
  }
  return directions;
}

SixWayFit::SixWayFit(std::vector<glm::vec3> directions) : directions_(std::move(directions)) {
  std::array<double, 36> gram{};
  for (const glm::vec3& d : directions_) {
    const std::array<float, 6> w = sixWayWeights(d);
    weights_.push_back({w[0], w[1], w[2], w[3], w[4], w[5]});
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) gram[i * 6 + j] += double(w[i]) * double(w[j]);
  }
  for (unsigned support = 1; support < 64; ++support) {
    std::vector<int> channels;
    for (int i = 0; i < 6; ++i)
      if (support & (1u << i)) channels.push_back(i);
    const int k = int(channels.size());
    std::vector<double> block(size_t(k) * k), inverse;
    for (int r = 0; r < k; ++r)
      for (int c = 0; c < k; ++c) block[size_t(r) * k + c] = gram[channels[r] * 6 + channels[c]];
    if (!invert(block, k, inverse))
      throw std::invalid_argument("six-way fit: " + std::to_string(directions_.size()) +
                                  " light directions do not light every channel apart from the others");
    for (int r = 0; r < k; ++r)
      for (int c = 0; c < k; ++c)
        inverses_[support][channels[r] * 6 + channels[c]] = inverse[size_t(r) * k + c];
  }
}

std::array<float, 6> SixWayFit::fit(std::span<const float> values) const {
  if (values.size() != directions_.size())
    throw std::invalid_argument("six-way fit: " + std::to_string(values.size()) + " values for " +
                                std::to_string(directions_.size()) + " directions");
  std::array<double, 6> b{};
  for (size_t j = 0; j < values.size(); ++j)
    for (int i = 0; i < 6; ++i) b[i] += weights_[j][i] * double(values[j]);
  std::array<double, 6> best{};  // the empty support: m = 0, b·m = 0
  double bestGain = 0.0;
  for (unsigned support = 1; support < 64; ++support) {
    std::array<double, 6> m{};
    bool feasible = true;
    double gain = 0.0;
    for (int r = 0; r < 6 && feasible; ++r) {
      if (!(support & (1u << r))) continue;
      for (int c = 0; c < 6; ++c) m[r] += inverses_[support][r * 6 + c] * b[c];
      feasible = m[r] >= 0.0;
      gain += b[r] * m[r];
    }
    if (feasible && gain > bestGain) {
      best = m;
      bestGain = gain;
    }
  }
  return {float(best[0]), float(best[1]), float(best[2]), float(best[3]), float(best[4]), float(best[5])};
}

}  // namespace sixway::reference
