#pragma once
// Projections as engines build them for Vulkan (NDC y = −1 at the top row, depth 0..1): standard, reversed-Z
// and with an infinite far plane, right-handed. For tests of the engine camera (render/engine_view.h).
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

namespace sixway::test {

// glm's projections put NDC y = +1 at the top; a Vulkan engine with a positive viewport negates row y.
inline glm::mat4 vulkanY(glm::mat4 p) {
  for (int c = 0; c < 4; ++c) p[c][1] = -p[c][1];
  return p;
}

enum class DepthConvention { Standard, Reversed, InfiniteStandard, InfiniteReversed };

// Depth 0 at near and 1 at far (Standard), the other way round (Reversed), or with the far plane at infinity:
// d = 1 − near / w (InfiniteStandard), d = near / w (InfiniteReversed).
inline glm::mat4 engineProjection(DepthConvention convention, float fovY, float aspect, float near,
                                  float far) {
  switch (convention) {
    case DepthConvention::Standard:
      return vulkanY(glm::perspectiveRH_ZO(fovY, aspect, near, far));
    case DepthConvention::Reversed:
      return vulkanY(glm::perspectiveRH_ZO(fovY, aspect, far, near));
    default: {
      const bool reversed = convention == DepthConvention::InfiniteReversed;
      const float f = 1.0f / std::tan(0.5f * fovY);
      glm::mat4 p(0.0f);
      p[0][0] = f / aspect;
      p[1][1] = f;
      p[2][3] = -1.0f;
      p[2][2] = reversed ? 0.0f : -1.0f;
      p[3][2] = reversed ? near : -near;
      return vulkanY(p);
    }
  }
}

// The depth-buffer value of `projection` at view depth v (right-handed: the point (0, 0, −v)), and what a
// cleared buffer holds (the far end: 1, or 0 reversed).
inline double depthAt(const glm::mat4& projection, double v) {
  return (-double(projection[2][2]) * v + double(projection[3][2])) / v;
}
inline double clearDepth(DepthConvention convention) {
  return convention == DepthConvention::Standard || convention == DepthConvention::InfiniteStandard ? 1.0
                                                                                                    : 0.0;
}

}  // namespace sixway::test
