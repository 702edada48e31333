#pragma once
// Scenes for the validation runs, in lattice units: cell size 1 m, one lattice step per 1 s frame,
// so speeds are cells/step and viscosities cells²/step.
#include <nlohmann/json.hpp>

#include <string>

#include "scene/scene.h"

namespace sixway::test {

// A scene with the given grid size and viscosity, no smoke source, all faces `faces`; `extra` is
// merged over it (nested objects merged key by key).
inline scene::Scene latticeScene(int nx, int ny, int nz, double viscosity, const std::string& faces,
                                 const nlohmann::json& extra = nlohmann::json::object()) {
  nlohmann::json j = {
      {"grid", {{"size", {nx, ny, nz}}, {"cell_size", 1.0}}},
      {"time", {{"frame_dt", 1.0}, {"steps_per_frame", 1}}},
      {"fluid", {{"viscosity", viscosity}, {"smagorinsky", 0.0}, {"max_lattice_velocity", 0.3}}},
      {"boundaries",
       {{"x-", faces}, {"x+", faces}, {"y-", faces}, {"y+", faces}, {"z-", faces}, {"z+", faces}}},
      {"camera", {{"position", {0, 0, 10}}, {"target", {0, 0, 0}}}},
  };
  j.merge_patch(extra);
  return scene::parseScene(j, "validation scene", ".");
}

// The fluid.population_storage patch of the fp16 runs (lbm_lattice.glsl), for `extra`.
inline nlohmann::json populationStorage(const std::string& storage) {
  return {{"fluid", {{"population_storage", storage}}}};
}

}  // namespace sixway::test
