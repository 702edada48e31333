#pragma once
// The command line's side of the device limits: a buffer or image that the device cannot hold is refused
// before allocation by src/gpu (gpu::LimitError, naming the resource); here it becomes bad input that names
// the file or option the user gave and the setting to reduce.
#include <string>

#include "gpu/check.h"
#include "io/error.h"
#include "scene/scene.h"

namespace sixway::app {

// build(), with a gpu::LimitError turned into an io::InputError "<source>: <problem>; reduce <setting>".
template <class Build>
auto withinDeviceLimits(const std::string& source, const std::string& setting, Build&& build) {
  try {
    return build();
  } catch (const gpu::LimitError& e) {
    throw io::InputError(source, e.problem() + "; reduce " + setting);
  }
}

// What to reduce when a scene's lattice does not fit: "grid.size (NX×NY×NZ) or grid.smoke_upres (N)".
std::string gridSetting(const scene::Grid& grid);

}  // namespace sixway::app
