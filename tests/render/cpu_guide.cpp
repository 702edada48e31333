#include "cpu_guide.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <stdexcept>

namespace sixway::test {
namespace {

constexpr double kStopTransmittance = 1e-3;  // as the GPU: stop once T < this and the shell is found
constexpr double kOpacityLevels[4] = {0.1, 0.35, 0.6, 0.85};  // shaders/common/depth.glsl

uint32_t pcgHash(uint32_t v) {
  const uint32_t state = v * 747796405u + 2891336453u;
  const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// A light grid's optical depths with trilinear interpolation between nodes, clamped to the outer nodes.
struct GridDepth {
  render::LightGrid grid;
  std::vector<double> depths;

  double at(dvec3 p) const { return interpolate(p, false); }
  // The optical depth through the whole column at p (its last node).
  double columnTotal(dvec3 p) const { return interpolate(p, true); }

  double interpolate(dvec3 p, bool lastNode) const {
    const dvec3 r = p - dvec3(grid.corner);
    const double coord[3] = {
        glm::dot(r, dvec3(grid.u)) / grid.spacing, glm::dot(r, dvec3(grid.v)) / grid.spacing,
        lastNode ? grid.nodes.z - 1.0 : -glm::dot(r, dvec3(grid.toLight)) / grid.interval};
    int i0[3], i1[3];
    double f[3];
    for (int a = 0; a < 3; ++a) {
      const double c = std::clamp(coord[a], 0.0, double(grid.nodes[a] - 1));
      i0[a] = std::min(int(std::floor(c)), grid.nodes[a] - 1);
      i1[a] = std::min(i0[a] + 1, grid.nodes[a] - 1);
      f[a] = c - i0[a];
    }
    double result = 0;
    for (int corner = 0; corner < 8; ++corner) {
      const int a = (corner & 1) ? i1[0] : i0[0], b = (corner & 2) ? i1[1] : i0[1],
                c = (corner & 4) ? i1[2] : i0[2];
      const double w = ((corner & 1) ? f[0] : 1 - f[0]) * ((corner & 2) ? f[1] : 1 - f[1]) *
                       ((corner & 4) ? f[2] : 1 - f[2]);
      result += w * depths[(size_t(c) * grid.nodes.y + b) * grid.nodes.x + a];
    }
    return result;
  }
};

}  // namespace

double guideJitter(uint32_t seed, uint32_t pixel, uint32_t frame) {
  uint32_t state = pcgHash(seed ^ pcgHash(pixel ^ pcgHash(frame)));
  state = state * 747796405u + 2891336453u;
  const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return double(((word >> 22u) ^ word) >> 8u) / 16777216.0;
}

namespace {

dvec3 towardLight(scene::GuideLight light, const render::Camera& c) {
  switch (light) {
    case scene::GuideLight::Right:
      return c.right;
    case scene::GuideLight::Left:
      return -dvec3(c.right);
    case scene::GuideLight::Top:
      return c.up;
    case scene::GuideLight::Bottom:
      return -dvec3(c.up);
    case scene::GuideLight::Back:
      return c.forward;
    case scene::GuideLight::Front:
      break;
  }
  return -dvec3(c.forward);
}

// A guide light other than front: the grid along its axis, and whether it lies at the grid's far end (its
// optical depth is then the column's total less the grid's).
struct ShadowedLight {
  dvec3 toLight;
  const GridDepth* grid;
  bool opposite;
};

}  // namespace

io::Image cpuGuidingMap(const CpuVolume& volume, const scene::Smoke& smoke, const render::Camera& camera,
                        const render::ImagePlane& billboard, const render::DepthRange& shellRange,
                        const render::GuideSettings& settings, const std::vector<render::LightGrid>& grids,
                        uint32_t frame) {
  std::vector<GridDepth> depths;
  for (const render::LightGrid& g : grids)
    depths.push_back({g, lightGridDepths(volume, smoke.extinction, g)});
  bool front = false;
  std::vector<ShadowedLight> lights;
  for (scene::GuideLight light : settings.lights) {
    if (light == scene::GuideLight::Front) {
      front = true;
      continue;
    }
    const dvec3 d = towardLight(light, camera);
    for (const GridDepth& g : depths) {
      const double along = glm::dot(dvec3(g.grid.toLight), d);
      if (std::fabs(along) > 0.999) lights.push_back({d, &g, along < 0});
    }
  }
  if (lights.size() + front != settings.lights.size())
    throw std::invalid_argument("cpuGuidingMap: a guide light has no light grid");
  const int size = int(settings.size);
  const double h = settings.stepCells * volume.grid.cellSize;
  const double albedoPi = smoke.albedo * std::numbers::pi;
  const dvec3 origin = camera.position, forward = camera.forward;
  io::Image image(size, size,
                  {"guide", "alpha", "depth", "level 0.1", "level 0.35", "level 0.6", "level 0.85"});
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const dvec3 dir = cameraRay(camera, billboard, {x + 0.5, y + 0.5}, size, size);
      const auto [entry, exit] = rayBox(origin, dir, volume.box());
      double transmittance = 1, radiance = 0, shell = -1;
      // The view depths where the opacity first reaches each level (−1: not yet).
      std::array<double, 4> levels = {-1, -1, -1, -1};
      const auto crossLevels = [&](double before, double after, double sigma, double t, double slabLength,
                                   std::array<double, 4>& into) {
        for (int k = 0; k < 4; ++k) {
          if (into[k] >= 0 || 1 - after < kOpacityLevels[k]) continue;
          into[k] = (t + std::clamp(std::log(before / (1 - kOpacityLevels[k])) / sigma, 0.0, slabLength)) *
                    glm::dot(dir, forward);
        }
      };
      if (entry < exit) {
        const double u = guideJitter(settings.seed, uint32_t(y * size + x), frame);
        const int samples = std::max(0, int(std::ceil((exit - entry) / h - u)));
        for (int i = 0; i < samples && (transmittance > kStopTransmittance || shell < 0); ++i) {
          const double t = entry + (u + i) * h;
          const dvec3 p = origin + t * dir;
          const double sigma = smoke.extinction * volume.densityAt(p);
          if (sigma <= 0) continue;
          const double slab = std::exp(-sigma * h);
          // Front: the light's path is the view path, T_light = T·e^{−σ s} in the slab, so
          // ∫_0^h σ_s T² e^{−2σ s} ds = albedo · T² (1 − e^{−2σh}) / 2.
          if (front)
            radiance += albedoPi * henyeyGreenstein(glm::dot(-forward, dir), smoke.phaseG) * transmittance *
                        transmittance * (1 - slab * slab) / 2;
          for (const ShadowedLight& light : lights) {
            const double tau =
                light.opposite ? light.grid->columnTotal(p) - light.grid->at(p) : light.grid->at(p);
            radiance += transmittance * (1 - slab) * albedoPi *
                        henyeyGreenstein(glm::dot(light.toLight, dir), smoke.phaseG) * std::exp(-tau);
          }
          const double after = transmittance * slab;
          crossLevels(transmittance, after, sigma, t - h / 2, h, levels);
          if (shell < 0 && 1 - after >= settings.shellThreshold) {
            const double s =
                std::clamp(std::log(transmittance / (1 - settings.shellThreshold)) / sigma, 0.0, h);
            shell = (t - h / 2 + s) * glm::dot(dir, forward);
          }
          transmittance = after;
        }
      }
      image.at(x, y, 0) = float(radiance);
      image.at(x, y, 1) = float(1 - transmittance);
      // With the fine march, the levels are its midpoint steps' (not jittered), until T < 1e-4 as the GPU's.
      if (settings.alphaStepCells > 0 && entry < exit) {
        const double step = settings.alphaStepCells * volume.grid.cellSize;
        levels = {-1, -1, -1, -1};
        double tau = 0;
        for (double t0 = entry; t0 < exit && tau < 9.2; t0 += step) {
          const double dt = std::min(step, exit - t0);
          const double sigma = smoke.extinction * volume.densityAt(origin + (t0 + dt / 2) * dir);
          if (sigma > 0) crossLevels(std::exp(-tau), std::exp(-tau - sigma * dt), sigma, t0, dt, levels);
          tau += sigma * dt;
        }
      }
      const double span = shellRange.far - shellRange.near;
      image.at(x, y, 2) = shell < 0 ? 1.0f : float(std::clamp((shell - shellRange.near) / span, 0.0, 1.0));
      for (int k = 0; k < 4; ++k)
        image.at(x, y, 3 + k) =
            levels[k] < 0 ? 1.0f : float(std::clamp((levels[k] - shellRange.near) / span, 0.0, 1.0));
    }
  return image;
}

}  // namespace sixway::test
