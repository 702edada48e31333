#pragma once
// CPU oracles for the reference renderers, in double precision and written independently of the shaders
// from the definitions in docs/reference-rendering.md: volume sampling, camera rays, optical depth by
// direct marching toward a light, the single-scattering six-way lightmaps, and single scattering of an
// environment or a point light. Slow and simple; for volumes of a few thousand cells and small images.
#include <array>
#include <functional>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "io/image.h"
#include "render/camera.h"
#include "render/light_grid.h"
#include "render/volume.h"
#include "scene/scene.h"

namespace sixway::test {

using glm::dvec3;

struct CpuVolume {
  render::VolumeGrid grid;
  std::vector<float> density;
  std::vector<float> temperature;  // empty: 0 everywhere

  // Trilinear between cell centres, clamped to the outer cells inside the box, zero outside; negative → 0.
  double densityAt(dvec3 p) const;
  double temperatureAt(dvec3 p) const;
  render::Box box() const { return grid.bounds(); }
};

// A volume whose density (and temperature) is f(cell centre).
CpuVolume makeVolume(glm::ivec3 size, glm::vec3 origin, float cellSize,
                     const std::function<float(dvec3)>& density,
                     const std::function<float(dvec3)>& temperature = nullptr);

// Entry and exit distances of the ray o + t·d (t >= 0) through the box; {0, 0} or entry >= exit when missed.
std::array<double, 2> rayBox(dvec3 o, dvec3 d, const render::Box& box);

// The camera ray through pixel coordinate `pixel` (centres at x + 0.5) of a W × H image over `plane`.
dvec3 cameraRay(const render::Camera& camera, const render::ImagePlane& plane, glm::dvec2 pixel, int width,
                int height);

// ∫ σ_t ds from p along `dir` up to the box's far side or tMax, midpoint rule with steps of at most maxStep.
double opticalDepth(const CpuVolume& volume, double extinction, dvec3 p, dvec3 dir, double maxStep,
                    double tMax = 1e300);

// The optical depth at every node of a light grid (the baker's light_depth pass), node index
// (c · ny + b) · nx + a: each interval between nodes clipped to the box, equal midpoint steps.
std::vector<double> lightGridDepths(const CpuVolume& volume, double extinction,
                                    const render::LightGrid& grid);

// The eight six-way channels, by a view march with steps of at most stepCells cells and a direct march
// toward each light from every sample; the lights come from the camera's six-way axes, or from `lights`
// (unit, world space, toward the light) when given.
io::Image bakeSixWay(const CpuVolume& volume, const scene::Smoke& smoke, const render::Camera& camera,
                     const render::ImagePlane& plane, int width, int height, double stepCells,
                     const std::array<glm::vec3, 6>* lights = nullptr);

// Single scattering toward the camera (RGB, black background) of light arriving from every direction with
// radiance max(0, L0 + L1·w), integrated over `directions` quasi-uniform directions (spherical Fibonacci).
io::Image environmentSingleScattering(const CpuVolume& volume, const scene::Smoke& smoke,
                                      const render::Camera& camera, const render::ImagePlane& plane,
                                      int width, int height, const std::array<glm::vec3, 4>& environment,
                                      int directions, double stepCells);

// Single scattering toward the camera (RGB, black background) of a point light of radiant intensity
// `intensity` (colour included) at `position`.
io::Image pointLightSingleScattering(const CpuVolume& volume, const scene::Smoke& smoke,
                                     const render::Camera& camera, const render::ImagePlane& plane, int width,
                                     int height, glm::vec3 position, glm::vec3 intensity, double stepCells);

// The Henyey–Greenstein phase function of the cosine between propagation directions.
double henyeyGreenstein(double cosTheta, double g);

}  // namespace sixway::test
