#pragma once
// The small volumes, optics and views the render tests share.
#include <glm/vec3.hpp>

#include "cpu_reference.h"
#include "render/billboard.h"
#include "render/camera.h"
#include "render/volume.h"
#include "scene/scene.h"
#include "support/gpu_fixture.h"

namespace sixway::test {

// A smooth smoke-like volume in the unit box [0, 1]³: three overlapping Gaussian puffs (density up to
// about 1) and a temperature that rises toward the top.
CpuVolume puffs(int cells);

// Small cones of smoke with exactly zero density between them, some on the faces between the 8³-cell bricks
// of the empty-space skipping: most bricks are empty, and smoke crosses brick faces.
CpuVolume sparseCones(int cells);

// A box of constant density `density` (cells everywhere the same).
CpuVolume constantBox(glm::ivec3 cells, float cellSize, float density);

// Optics with extinction so that the puffs are a few optical depths across, and an emission ramp.
scene::Smoke puffOptics();

// An oblique perspective view of the unit box from the front-right-above.
render::Camera obliqueCamera();

// The square billboard of `box` for `camera`.
render::ImagePlane squareBillboard(const render::Camera& camera, const render::Box& box);

class RenderTest : public GpuTest {
 protected:
  static render::DeviceVolume upload(const CpuVolume& volume);
};

}  // namespace sixway::test
