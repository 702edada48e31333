#pragma once
// CPU oracle of the motion field (docs/dataset-format.md, "Motion field"), in double precision, written from
// the definition: per billboard pixel, the shell point p at the guide's decoded shell depth, the velocity
// there (trilinear between cell centres, clamped at the outer centres, zero outside the grid), the
// displacement d = velocity · interval, and motion = pixel(p) − pixel(p − d) in billboard pixels (y down).
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "render/camera.h"
#include "render/projection.h"
#include "render/volume.h"

namespace sixway::test {

struct CpuVelocityGrid {
  render::VolumeGrid grid;
  std::vector<glm::dvec3> velocity;  // m/s per cell, x fastest
};

// `shellDepth`: the guide's B channel per pixel (row-major, size²), 1 where there is no shell.
std::vector<glm::dvec2> cpuMotionField(const render::Camera& camera, const render::ImagePlane& billboard,
                                       const render::DepthRange& shellRange,
                                       const std::vector<float>& shellDepth, int size,
                                       const CpuVelocityGrid& velocity, double intervalSeconds);

}  // namespace sixway::test
