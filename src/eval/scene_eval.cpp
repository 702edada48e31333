#include "eval/scene_eval.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "eval/scene_evaluation.h"
#include "io/error.h"
#include "io/report.h"
#include "runtime/internal.h"
#include "runtime/network_weights.h"
#include "scene/scene.h"

namespace sixway::eval {
namespace {

namespace fs = std::filesystem;

// The scene as evaluated: the density scale on the extinction (σ_t = extinction · density, so scaling one
// scales the other for every renderer), and the camera path replaced when asked.
scene::Scene evaluatedScene(const SceneEvalSettings& s) {
  scene::Scene scene = scene::loadScene(s.scene);
  scene.smoke.extinction *= s.densityScale;
  if (s.cameraOrbitDeg) scene.camera.path = scene::CameraOrbit{*s.cameraOrbitDeg};
  return scene;
}

void check(const SceneEvalSettings& s) {
  if (s.frames < 1) throw io::InputError("--frames", "give at least 1 frame with --scene");
  if (!(s.densityScale > 0.0f) || !std::isfinite(s.densityScale))
    throw io::InputError("--density-scale", "must be a positive number");
  if (s.stripFrame && (*s.stripFrame < 0 || *s.stripFrame >= s.frames))
    throw io::InputError("--strip-frame", "frame " + std::to_string(*s.stripFrame) + " is outside 0.." +
                                              std::to_string(s.frames - 1));
  runtime::readWeights(s.weights);  // a missing or malformed file fails before any work
}

}  // namespace

void evaluateScene(const DeviceOptions& device, const SceneEvalSettings& s) {
  check(s);
  scene::Scene scene = evaluatedScene(s);
  io::requireWritableFile(s.report, s.force);
  if (!s.out.empty()) io::requireWritableDirectory(s.out, s.force);

  const Device gpuDevice(device);
  SceneEvaluation evaluation(runtime::Access::context(gpuDevice), runtime::Access::pipelineCache(gpuDevice),
                             s, std::move(scene));
  if (!s.out.empty()) fs::create_directories(s.out);
  evaluation.run();
  if (gpuDevice.validationMessages() > 0)
    throw std::runtime_error(std::to_string(gpuDevice.validationMessages()) + " validation messages");
}

}  // namespace sixway::eval
