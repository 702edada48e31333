#pragma once
// CPU oracle of the guiding map (docs/real-time-rendering.md, "Guiding map"), in double precision and written
// from the documented formulas: the same jitter hash and seed, the same sample lattice, the front light
// through the view transmittance, the other lights through the optical depth on the same light grids (node
// depths integrated by the baker's oracle, lightGridDepths), interpolated trilinearly between nodes.
#include <cstdint>
#include <vector>

#include "cpu_reference.h"
#include "io/image.h"
#include "render/camera.h"
#include "render/guiding_map.h"
#include "render/light_grid.h"
#include "render/projection.h"
#include "scene/scene.h"

namespace sixway::test {

// The jitter u in [0, 1) of a pixel (index y · width + x) and frame: shaders/common/random.glsl's
// rngNext(rngSeed(seed, pixel, frame)).
double guideJitter(uint32_t seed, uint32_t pixel, uint32_t frame);

// Channels guide, alpha, depth (encoded as the GPU stores it), and the opacity depths: the view depths where
// the ray's opacity first reaches 0.1, 0.35, 0.6 and 0.85, exact within a slab (encoded as
// GuidingMap::opacityDepths holds them; 1 where not reached), from the fine march's midpoint steps where the
// settings have one, else from the coarse march's samples. `grids` are the light grids
// (GuidingMap::shadowGrids()); each guide light other than front uses the one along its axis, from its near
// end (grid pointing to it) or its far end (the column's total less the grid's depth).
io::Image cpuGuidingMap(const CpuVolume& volume, const scene::Smoke& smoke, const render::Camera& camera,
                        const render::ImagePlane& billboard, const render::DepthRange& shellRange,
                        const render::GuideSettings& settings, const std::vector<render::LightGrid>& grids,
                        uint32_t frame);

}  // namespace sixway::test
