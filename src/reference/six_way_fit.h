#pragma once
// The best six maps for the six-way blend (docs/reference-rendering.md, "The six-way ceiling"). An engine
// lights a six-way material from direction d (unit, six-way frame, toward the light) with t(d) = w(d)·m: the
// six maps m weighted by the squared components of d on the side d points to (sixWayTransmission,
// shaders/common/sixway_lighting.glsl). The axis-lit maps reproduce the smoke exactly under the six axis
// lights and only approximately in between; the maps fitted here minimise Σ_j (w(d_j)·m − r_j)² over lights
// from many directions d_j, where r_j is the smoke's value under the light from d_j, subject to m ≥ 0 (an
// engine's texture holds no negative light).
#include <array>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

namespace sixway::reference {

// The blend's weights of the six light channels (Right, Left, Top, Bottom, Back, Front) for the unit
// direction `d` in the six-way frame: d_i² for the channel on the side d points to, 0 for its opposite.
std::array<float, 6> sixWayWeights(glm::vec3 d);

// `count` unit directions spread evenly over the sphere (spherical Fibonacci: z = 1 − (2k + 1)/count, the
// azimuth advancing by the golden angle), in the six-way frame.
std::vector<glm::vec3> sphereDirections(int count);

class SixWayFit {
 public:
  // For lights from `directions` (unit, six-way frame). Throws std::invalid_argument unless every channel can
  // be told from the others (the weights' Gram matrix is positive definite).
  explicit SixWayFit(std::vector<glm::vec3> directions);

  // The maps m ≥ 0 that minimise Σ_j (w(d_j)·m − values_j)², values_j being the value under the light from
  // directions()[j]. Throws std::invalid_argument for another count of values.
  std::array<float, 6> fit(std::span<const float> values) const;

  const std::vector<glm::vec3>& directions() const { return directions_; }

 private:
  // The normal equations are G m = b with G = Σ_j w_j w_jᵀ, b = Σ_j values_j w_j. The constrained optimum is
  // the unconstrained optimum on its support F (the channels it leaves above 0), m_F = (G_FF)⁻¹ b_F, whose
  // objective is −½ b_F·m_F; so of the 64 supports, the one whose m_F ≥ 0 has the largest b_F·m_F is the
  // exact solution (non-negative least squares by enumeration, affordable for six unknowns).
  std::vector<glm::vec3> directions_;
  std::vector<std::array<double, 6>> weights_;
  std::array<std::array<double, 36>, 64> inverses_{};  // (G_FF)⁻¹ for support bits F, zero outside F
};

}  // namespace sixway::reference
