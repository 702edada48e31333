#pragma once
// reference-fit: the six lightmaps a six-way material can best use (six_way_fit.h) — the ceiling of six-way
// lighting, where the axis-lit maps (reference-ms) are one choice under it. The smoke is baked under lights
// from `directions` quasi-uniform directions (six per bake, all orders as ScatteredLightmaps bakes them);
// each texel's six maps are then fitted to those values (six_way_fit.h). Alpha and emissive do not depend on
// the lights: they are the first bake's. Cost: directions / 6 multiple-scattering bakes and the fit on the
// host.
#include <vector>

#include "reference/scattered_lightmaps.h"
#include "reference/six_way_fit.h"

namespace sixway::reference {

// `count` quasi-uniform directions (sphereDirections) for the fit: a multiple of 6 in 12..96; throws
// io::InputError (source "reference-fit") for another count.
std::vector<glm::vec3> fitDirections(int count);

class FittedLightmaps {
 public:
  // `directions`: unit, in the six-way frame, a multiple of 6 of them (at most 96) that tell every channel
  // from the others (SixWayFit); throws std::invalid_argument otherwise.
  FittedLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache,
                  std::vector<glm::vec3> directions);

  // The eight channels (sixWayChannelNames()) of `volume` from `camera` over `billboard`: the fitted six
  // maps, alpha and emissive. `settings.lights` must be unset (the lights are the fit's); each bake's higher
  // orders are traced with `multiple`, its seed advanced per bake.
  io::Image bake(const render::Volume& volume, const scene::Smoke& smoke, const render::Camera& camera,
                 const render::ImagePlane& billboard, const BakeSettings& settings,
                 const MultipleScattering& multiple);

  // The fit's directions in the six-way frame.
  const std::vector<glm::vec3>& directions() const { return fit_.directions(); }
  // GPU time of the last bake, its bakes' stages summed by name.
  const std::vector<gpu::StageTime>& stageTimes() const { return stages_; }

 private:
  ScatteredLightmaps baker_;
  SixWayFit fit_;
  std::vector<gpu::StageTime> stages_;
};

}  // namespace sixway::reference
