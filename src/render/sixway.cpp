#include "render/sixway.h"

namespace sixway::render {

const std::array<std::string, kSixWayChannels>& sixWayChannelNames() {
  static const std::array<std::string, kSixWayChannels> names = {"Right", "Left",  "Top",   "Bottom",
                                                                 "Back",  "Front", "alpha", "emissive"};
  return names;
}

std::array<glm::vec3, kSixWayLights> sixWayLightDirections(const Camera& camera) {
  return {camera.right, -camera.right, camera.up, -camera.up, camera.forward, -camera.forward};
}

}  // namespace sixway::render
