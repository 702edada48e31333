#include "cpu_reference.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

namespace sixway::test {
namespace {

constexpr double kPi = std::numbers::pi;

double trilinear(const render::VolumeGrid& grid, const std::vector<float>& values, dvec3 p) {
  const render::Box box = grid.bounds();
  for (int a = 0; a < 3; ++a)
    if (p[a] < box.min[a] || p[a] > box.max[a]) return 0.0;
  int i0[3], i1[3];
  double f[3];
  for (int a = 0; a < 3; ++a) {
    const double g = std::clamp((p[a] - grid.origin[a]) / grid.cellSize - 0.5, 0.0, double(grid.size[a] - 1));
    i0[a] = std::min(int(std::floor(g)), grid.size[a] - 1);
    i1[a] = std::min(i0[a] + 1, grid.size[a] - 1);
    f[a] = g - i0[a];
  }
  auto at = [&](int x, int y, int z) {
    return double(values[(size_t(z) * grid.size.y + y) * grid.size.x + x]);
  };
  double result = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const int x = (corner & 1) ? i1[0] : i0[0], y = (corner & 2) ? i1[1] : i0[1],
              z = (corner & 4) ? i1[2] : i0[2];
    const double w = ((corner & 1) ? f[0] : 1 - f[0]) * ((corner & 2) ? f[1] : 1 - f[1]) *
                     ((corner & 4) ? f[2] : 1 - f[2]);
    result += w * at(x, y, z);
  }
  return result;
}

glm::dvec3 rampColor(const scene::Emission& emission, double temperature) {
  const auto& keys = emission.ramp;
  if (temperature <= keys.front().temperature) return keys.front().color;
  for (size_t k = 1; k < keys.size(); ++k) {
    if (temperature <= keys[k].temperature) {
      const double s =
          (temperature - keys[k - 1].temperature) / (keys[k].temperature - keys[k - 1].temperature);
      return glm::dvec3(keys[k - 1].color) * (1 - s) + glm::dvec3(keys[k].color) * s;
    }
  }
  return keys.back().color;
}

double luminance(glm::dvec3 c) {
  return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

// Walks the camera ray of every pixel in steps of at most stepCells cells; `sample` gets the point, the
// ray direction and the fraction T·(1 − e^{−σ_t Δ}) of light that the step absorbs, and writes the pixel.
void marchPixels(const CpuVolume& volume, double extinction, const render::Camera& camera,
                 const render::ImagePlane& plane, int width, int height, double stepCells, io::Image& image,
                 const std::function<void(dvec3, dvec3, double, float*)>& sample,
                 const std::function<void(double, float*)>& finish) {
  const dvec3 origin = camera.position;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float* pixel = &image.pixels[image.index(x, y, 0)];
      const dvec3 dir = cameraRay(camera, plane, {x + 0.5, y + 0.5}, width, height);
      const auto [t0, t1] = rayBox(origin, dir, volume.box());
      double transmittance = 1.0;
      if (t0 < t1) {
        const int steps = int(std::ceil((t1 - t0) / (stepCells * volume.grid.cellSize)));
        const double dt = (t1 - t0) / steps;
        for (int i = 0; i < steps; ++i) {
          const dvec3 p = origin + (t0 + (i + 0.5) * dt) * dir;
          const double sigma = extinction * volume.densityAt(p);
          if (sigma <= 0) continue;
          const double segment = std::exp(-sigma * dt);
          sample(p, dir, transmittance * (1 - segment), pixel);
          transmittance *= segment;
        }
      }
      finish(transmittance, pixel);
    }
}

}  // namespace

double CpuVolume::densityAt(dvec3 p) const {
  return std::max(0.0, trilinear(grid, density, p));
}

double CpuVolume::temperatureAt(dvec3 p) const {
  return temperature.empty() ? 0.0 : trilinear(grid, temperature, p);
}

CpuVolume makeVolume(glm::ivec3 size, glm::vec3 origin, float cellSize,
                     const std::function<float(dvec3)>& density,
                     const std::function<float(dvec3)>& temperature) {
  CpuVolume v{{size, origin, cellSize}, {}, {}};
  for (int k = 0; k < size.z; ++k)
    for (int j = 0; j < size.y; ++j)
      for (int i = 0; i < size.x; ++i) {
        const dvec3 centre = dvec3(origin) + (dvec3(i, j, k) + 0.5) * double(cellSize);
        v.density.push_back(density(centre));
        if (temperature) v.temperature.push_back(temperature(centre));
      }
  return v;
}

std::array<double, 2> rayBox(dvec3 o, dvec3 d, const render::Box& box) {
  double t0 = 0.0, t1 = 1e300;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) {
      if (o[a] < box.min[a] || o[a] > box.max[a]) return {0.0, 0.0};
      continue;
    }
    double near = (box.min[a] - o[a]) / d[a], far = (box.max[a] - o[a]) / d[a];
    if (near > far) std::swap(near, far);
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
  }
  return {t0, t1};
}

dvec3 cameraRay(const render::Camera& camera, const render::ImagePlane& plane, glm::dvec2 pixel, int width,
                int height) {
  const double u = pixel.x / width, v = pixel.y / height;
  const double qx = plane.min.x + u * (double(plane.max.x) - plane.min.x);
  const double qy = plane.max.y - v * (double(plane.max.y) - plane.min.y);
  return glm::normalize(dvec3(camera.forward) + qx * dvec3(camera.right) + qy * dvec3(camera.up));
}

double opticalDepth(const CpuVolume& volume, double extinction, dvec3 p, dvec3 dir, double maxStep,
                    double tMax) {
  const auto [t0, t1] = rayBox(p, dir, volume.box());
  const double end = std::min(t1, tMax);
  if (!(end > t0)) return 0.0;
  const int steps = int(std::ceil((end - t0) / maxStep));
  const double dt = (end - t0) / steps;
  double tau = 0.0;
  for (int i = 0; i < steps; ++i) tau += dt * extinction * volume.densityAt(p + (t0 + (i + 0.5) * dt) * dir);
  return tau;
}

std::vector<double> lightGridDepths(const CpuVolume& volume, double extinction,
                                    const render::LightGrid& grid) {
  std::vector<double> depths(grid.nodeCount());
  const dvec3 away = -dvec3(grid.toLight);
  for (int b = 0; b < grid.nodes.y; ++b)
    for (int a = 0; a < grid.nodes.x; ++a) {
      const dvec3 start = grid.node(a, b, 0);
      const auto [in, out] = rayBox(start, away, volume.box());
      double tau = 0.0;
      for (int c = 0; c < grid.nodes.z; ++c) {
        if (c > 0) {
          const double t0 = std::max((c - 1) * double(grid.interval), in),
                       t1 = std::min(c * double(grid.interval), out);
          if (t1 > t0) {
            const int steps = int(std::ceil((t1 - t0) / grid.maxStep));
            const double h = (t1 - t0) / steps;
            for (int s = 0; s < steps; ++s)
              tau += h * extinction * volume.densityAt(start + (t0 + (s + 0.5) * h) * away);
          }
        }
        depths[(size_t(c) * grid.nodes.y + b) * grid.nodes.x + a] = tau;
      }
    }
  return depths;
}

double henyeyGreenstein(double cosTheta, double g) {
  const double d = 1 + g * g - 2 * g * cosTheta;
  return (1 - g * g) / (4 * kPi * d * std::sqrt(d));
}

io::Image bakeSixWay(const CpuVolume& volume, const scene::Smoke& smoke, const render::Camera& camera,
                     const render::ImagePlane& plane, int width, int height, double stepCells,
                     const std::array<glm::vec3, 6>* customLights) {
  io::Image image(width, height, {"Right", "Left", "Top", "Bottom", "Back", "Front", "alpha", "emissive"});
  std::array<dvec3, 6> lights = {dvec3(camera.right), -dvec3(camera.right),  dvec3(camera.up),
                                 -dvec3(camera.up),   dvec3(camera.forward), -dvec3(camera.forward)};
  if (customLights)
    for (int l = 0; l < 6; ++l) lights[l] = glm::normalize(dvec3((*customLights)[l]));
  const double maxStep = stepCells * volume.grid.cellSize;
  const bool emits = smoke.emission.intensity > 0 && !smoke.emission.ramp.empty();
  marchPixels(
      volume, smoke.extinction, camera, plane, width, height, stepCells, image,
      [&](dvec3 p, dvec3 dir, double absorbed, float* pixel) {
        for (int l = 0; l < 6; ++l) {
          const double lightT = std::exp(-opticalDepth(volume, smoke.extinction, p, lights[l], maxStep));
          pixel[l] += float(absorbed * smoke.albedo * kPi *
                            henyeyGreenstein(glm::dot(lights[l], dir), smoke.phaseG) * lightT);
        }
        if (emits)
          pixel[7] += float(absorbed * smoke.emission.intensity / smoke.extinction *
                            luminance(rampColor(smoke.emission, volume.temperatureAt(p))));
      },
      [](double transmittance, float* pixel) { pixel[6] = float(1 - transmittance); });
  return image;
}

io::Image environmentSingleScattering(const CpuVolume& volume, const scene::Smoke& smoke,
                                      const render::Camera& camera, const render::ImagePlane& plane,
                                      int width, int height, const std::array<glm::vec3, 4>& environment,
                                      int directions, double stepCells) {
  std::vector<dvec3> dirs(directions);
  const double golden = kPi * (3 - std::sqrt(5.0));
  for (int k = 0; k < directions; ++k) {
    const double z = 1 - (2 * k + 1.0) / directions, r = std::sqrt(1 - z * z);
    dirs[k] = {r * std::cos(golden * k), r * std::sin(golden * k), z};
  }
  auto radianceFrom = [&](dvec3 w) {
    return glm::max(dvec3(environment[0]) + w.x * dvec3(environment[1]) + w.y * dvec3(environment[2]) +
                        w.z * dvec3(environment[3]),
                    dvec3(0.0));
  };
  const double maxStep = stepCells * volume.grid.cellSize;
  io::Image image(width, height, {"R", "G", "B"});
  marchPixels(
      volume, smoke.extinction, camera, plane, width, height, stepCells, image,
      [&](dvec3 p, dvec3 dir, double absorbed, float* pixel) {
        dvec3 inScattered(0.0);
        for (const dvec3& w : dirs)
          inScattered += radianceFrom(w) * henyeyGreenstein(glm::dot(w, dir), smoke.phaseG) *
                         std::exp(-opticalDepth(volume, smoke.extinction, p, w, maxStep));
        inScattered *= 4 * kPi / directions;
        for (int c = 0; c < 3; ++c) pixel[c] += float(absorbed * smoke.albedo * inScattered[c]);
      },
      [](double, float*) {});
  return image;
}

io::Image pointLightSingleScattering(const CpuVolume& volume, const scene::Smoke& smoke,
                                     const render::Camera& camera, const render::ImagePlane& plane, int width,
                                     int height, glm::vec3 position, glm::vec3 intensity, double stepCells) {
  const double maxStep = stepCells * volume.grid.cellSize;
  io::Image image(width, height, {"R", "G", "B"});
  marchPixels(
      volume, smoke.extinction, camera, plane, width, height, stepCells, image,
      [&](dvec3 p, dvec3 dir, double absorbed, float* pixel) {
        const dvec3 toLight = dvec3(position) - p;
        const double r = glm::length(toLight);
        const dvec3 d = toLight / r;
        const double lit = std::exp(-opticalDepth(volume, smoke.extinction, p, d, maxStep, r)) / (r * r) *
                           henyeyGreenstein(glm::dot(d, dir), smoke.phaseG) * smoke.albedo * absorbed;
        for (int c = 0; c < 3; ++c) pixel[c] += float(lit * intensity[c]);
      },
      [](double, float*) {});
  return image;
}

}  // namespace sixway::test
