#pragma once
// The six-way frame and the eight lightmap channels (docs/conventions.md, "Six-way frame", "Channels and
// packing"): per billboard, +x = camera right, +y = camera up, +z = away from the camera; "Right" is lit by a
// white directional light from camera right (direction toward the light d = +x), "Back" from behind the smoke
// (d = +z), "Front" from the camera's side (d = −z).
#include <array>
#include <glm/vec3.hpp>
#include <string>

#include "render/camera.h"

namespace sixway::render {

// Channel order of every eight-channel six-way image in sixway (bake output, path-traced lightmaps).
enum SixWayChannel { Right, Left, Top, Bottom, Back, Front, Alpha, Emissive };
constexpr int kSixWayChannels = 8;
constexpr int kSixWayLights = 6;

// Channel names, as used in per-frame EXR files: Right, Left, Top, Bottom, Back, Front, alpha, emissive.
const std::array<std::string, kSixWayChannels>& sixWayChannelNames();

// The six light directions (unit, world space, toward the light) of a camera, in channel order.
std::array<glm::vec3, kSixWayLights> sixWayLightDirections(const Camera& camera);

}  // namespace sixway::render
