#include "test_volumes.h"

#include <cmath>

namespace sixway::test {

CpuVolume puffs(int cells) {
  auto gauss = [](dvec3 p, dvec3 c, double r) {
    const dvec3 d = p - c;
    return std::exp(-(d.x * d.x + d.y * d.y + d.z * d.z) / (r * r));
  };
  return makeVolume(
      glm::ivec3(cells), glm::vec3(0.0f), 1.0f / float(cells),
      [&](dvec3 p) {
        return float(0.9 * gauss(p, {0.45, 0.4, 0.5}, 0.22) + 0.6 * gauss(p, {0.62, 0.62, 0.45}, 0.16) +
                     0.5 * gauss(p, {0.35, 0.7, 0.6}, 0.12));
      },
      [](dvec3 p) { return float(p.y * 1.2 - 0.1); });
}

CpuVolume sparseCones(int cells) {
  struct Cone {
    dvec3 centre;
    double radius, peak;
  };
  const Cone cones[] = {
      {{1.0 / 3, 0.5, 0.5}, 0.08, 1.5}, {{2.0 / 3, 1.0 / 3, 0.6}, 0.06, 2.0}, {{0.2, 0.75, 0.3}, 0.1, 1.0}};
  return makeVolume(glm::ivec3(cells), glm::vec3(0.0f), 1.0f / float(cells), [&](dvec3 p) {
    double d = 0;
    for (const Cone& c : cones) {
      const dvec3 r = p - c.centre;
      d += c.peak * std::max(0.0, 1.0 - std::sqrt(r.x * r.x + r.y * r.y + r.z * r.z) / c.radius);
    }
    return float(d);
  });
}

CpuVolume constantBox(glm::ivec3 cells, float cellSize, float density) {
  return makeVolume(cells, glm::vec3(0.0f), cellSize, [density](dvec3) { return density; });
}

scene::Smoke puffOptics() {
  scene::Smoke smoke;
  smoke.extinction = 6.0f;
  smoke.albedo = 0.8f;
  smoke.phaseG = 0.4f;
  smoke.emission.intensity = 2.0f;
  smoke.emission.ramp = {{0.2f, {0.0f, 0.0f, 0.0f}}, {0.6f, {1.0f, 0.4f, 0.1f}}, {1.0f, {1.0f, 0.9f, 0.7f}}};
  return smoke;
}

render::Camera obliqueCamera() {
  return render::Camera::lookAt({1.6f, 1.2f, 2.3f}, {0.5f, 0.5f, 0.5f}, {0.0f, 1.0f, 0.0f}, 40.0f);
}

render::ImagePlane squareBillboard(const render::Camera& camera, const render::Box& box) {
  return render::billboardBounds(camera, box, 1.0f);
}

render::DeviceVolume RenderTest::upload(const CpuVolume& volume) {
  render::DeviceVolume device(context(), volume.grid, !volume.temperature.empty());
  device.upload(volume.density, volume.temperature);
  return device;
}

}  // namespace sixway::test
