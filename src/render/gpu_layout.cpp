#include "render/gpu_layout.h"

#include <string>

#include "io/error.h"

namespace sixway::render::layout {

VolumeGrid volumeGrid(const render::VolumeGrid& grid) {
  return {glm::vec4(grid.origin, grid.cellSize), glm::ivec4(grid.size, 0)};
}

CameraRays cameraRays(const Camera& camera, const ImagePlane& plane) {
  return {glm::vec4(camera.position, 1.0f), glm::vec4(camera.right, 0.0f), glm::vec4(camera.up, 0.0f),
          glm::vec4(camera.forward, 0.0f), glm::vec4(plane.min, plane.max)};
}

LightGrid lightGrid(const render::LightGrid& grid) {
  return {glm::vec4(grid.corner, grid.spacing), glm::vec4(grid.u, grid.interval),
          glm::vec4(grid.v, grid.maxStep), glm::vec4(grid.toLight, 0.0f), glm::ivec4(grid.nodes, 0)};
}

int emissionRamp(const scene::Emission& emission, glm::vec4 (&keys)[kMaxRampKeys]) {
  if (emission.intensity <= 0.0f || emission.ramp.empty()) return 0;
  if (emission.ramp.size() > kMaxRampKeys)
    throw io::InputError("smoke.emission.ramp", "has " + std::to_string(emission.ramp.size()) +
                                                    " keys; the renderers take at most " +
                                                    std::to_string(kMaxRampKeys));
  for (size_t k = 0; k < emission.ramp.size(); ++k)
    keys[k] = glm::vec4(emission.ramp[k].temperature, emission.ramp[k].color);
  return int(emission.ramp.size());
}

}  // namespace sixway::render::layout
