#pragma once
// Errors that a scene's numbers cause while its frames run, without naming the scene: the camera's (it cannot
// see the volume at some frame of its path) and the simulation watchdog's. A command that runs a scene's
// frames wraps them in namingScene, so the line names the file (or the options) to fix, as `sim` does.
#include <filesystem>
#include <string>
#include <utility>

#include "render/camera_error.h"
#include "sim/watchdog.h"

namespace sixway::app {

// Runs `work`, naming `scene` in the watchdog's errors and `camera` (the scene, or the options that placed
// the camera) in the camera's.
template <typename Work>
decltype(auto) namingScene(const std::filesystem::path& scene, const std::filesystem::path& camera,
                           Work&& work) {
  try {
    return work();
  } catch (const render::CameraError& e) {
    throw io::InputError(camera.string(), e.what());
  } catch (const sim::WatchdogError& e) {
    throw sim::WatchdogError(scene.string() + ": " + e.what());
  }
}

template <typename Work>
decltype(auto) namingScene(const std::filesystem::path& scene, Work&& work) {
  return namingScene(scene, scene, std::forward<Work>(work));
}

}  // namespace sixway::app
