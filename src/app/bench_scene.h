#pragma once
// The fixed scene of `sixway bench`: assets/scenes/bench.json (a buoyant plume from a disk inlet around a
// sphere, a directional and a point light, a 512² frame) at any lattice size, and the smoke it starts from.
#include <filesystem>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "scene/scene.h"

namespace sixway::app {

// The scene with `lattice` cells: the cell size is scaled with the x resolution, so the domain keeps its
// width (and its shape when the lattice keeps the file's proportions, 1:2:1).
scene::Scene benchScene(const std::filesystem::path& file, glm::ivec3 lattice);

// (density, temperature) on the scene's smoke grid, x fastest: a fixed, seeded plume column above the first
// inlet, widening with height, with value noise in it and none inside sphere obstacles. The benchmark starts
// from it so that every stage sees a grown plume from the first frame (empty space is skipped by the guide,
// so a young plume would flatter it) without simulating hundreds of steps first.
std::vector<glm::vec2> benchSmoke(const scene::Scene& scene);

}  // namespace sixway::app
