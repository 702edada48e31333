#include "cpu_motion.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace sixway::test {
namespace {

using glm::dvec2, glm::dvec3;

dvec3 trilinear(const CpuVelocityGrid& v, dvec3 p) {
  const render::VolumeGrid& g = v.grid;
  const dvec3 lo(g.origin), hi = lo + dvec3(g.size) * double(g.cellSize);
  for (int a = 0; a < 3; ++a)
    if (p[a] < lo[a] || p[a] > hi[a]) return dvec3(0.0);
  const dvec3 c = glm::clamp((p - lo) / double(g.cellSize) - 0.5, dvec3(0.0), dvec3(g.size - 1));
  const glm::ivec3 i0 = glm::min(glm::ivec3(glm::floor(c)), g.size - 1);
  const dvec3 f = c - dvec3(i0);
  dvec3 sum(0.0);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::ivec3 o(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    const glm::ivec3 i = glm::min(i0 + o, g.size - 1);
    double w = 1;
    for (int a = 0; a < 3; ++a) w *= o[a] ? f[a] : 1 - f[a];
    sum += w * v.velocity[(size_t(i.z) * g.size.y + i.y) * g.size.x + i.x];
  }
  return sum;
}

}  // namespace

std::vector<dvec2> cpuMotionField(const render::Camera& camera, const render::ImagePlane& billboard,
                                  const render::DepthRange& shellRange, const std::vector<float>& shellDepth,
                                  int size, const CpuVelocityGrid& velocity, double intervalSeconds) {
  const dvec3 eye(camera.position), right(camera.right), up(camera.up), forward(camera.forward);
  const dvec2 lo(billboard.min), hi(billboard.max);
  // Image-plane point (distance 1) → billboard pixels, row 0 at the top.
  const auto pixelOf = [&](dvec2 q) {
    return dvec2((q.x - lo.x) / (hi.x - lo.x), (hi.y - q.y) / (hi.y - lo.y)) * double(size);
  };
  std::vector<dvec2> motion(size_t(size) * size, dvec2(0.0));
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const float encoded = shellDepth[size_t(y) * size + x];
      if (encoded >= 1.0f) continue;
      const dvec2 q(lo.x + (x + 0.5) / size * (hi.x - lo.x), hi.y - (y + 0.5) / size * (hi.y - lo.y));
      const double z = shellRange.near + double(encoded) * (shellRange.far - shellRange.near);
      const dvec3 p = eye + z * (forward + q.x * right + q.y * up);
      const dvec3 before = p - trilinear(velocity, p) * intervalSeconds - eye;
      const double depth = glm::dot(before, forward);
      if (depth <= 0) continue;
      motion[size_t(y) * size + x] =
          pixelOf(q) - pixelOf(dvec2(glm::dot(before, right), glm::dot(before, up)) / depth);
    }
  return motion;
}

}  // namespace sixway::test
