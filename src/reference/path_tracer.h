#pragma once
// The volumetric path tracer (Monte Carlo, unbiased; shaders/render/path_trace.comp): delta tracking for
// free paths, ratio tracking for shadow rays and alpha, Henyey–Greenstein phase sampling, any number of
// scattering orders, directional and point lights, emission, a constant background and an L1 environment.
// Samples accumulate progressively; a fixed seed gives the same image however the samples are split into
// passes. It renders final images under arbitrary lights and six-way lightmaps with multiple scattering.
#include <array>
#include <cstdint>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/sequence.h"
#include "io/image.h"
#include "render/brick_majorants.h"
#include "render/camera.h"
#include "render/obstacle_bvh.h"
#include "render/recorded_sequence.h"
#include "render/volume.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Context;
class Pipeline;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::reference {

struct TraceSettings {
  int width = 128, height = 128;
  uint32_t seed = 1;
  int maxOrders = 64;  // scattering orders followed (1 = single scattering, 0 = none)
  // The lowest scattering order whose light is recorded (2: multiple scattering only, and in six-way mode the
  // emission only once it has been scattered).
  int minOrder = 1;
  bool jitter = true;       // random points inside pixels; false: pixel centres, as the baker samples
  int samplesPerPass = 4;   // samples per pixel in one dispatch
  int brickCells = 8;       // side of the majorant bricks, in cells
  glm::vec3 background{0};  // radiance seen where camera rays leave the volume
  // Radiance arriving from direction w (world) at scattered rays that leave the volume: max(0, L0 + L1·w),
  // as {L0, L1x, L1y, L1z}.
  std::array<glm::vec3, 4> environment{};
  // Six-way mode: unit directions toward the six channels' lights, in world space; unset: the camera's
  // six-way axes (as BakeSettings::lights).
  std::optional<std::array<glm::vec3, 6>> sixWayLights;
};

class PathTracer {
 public:
  PathTracer(const gpu::Context& context, const gpu::PipelineCache& cache);
  ~PathTracer();

  // Starts an image of `volume` under `lights` (positioned for the frame; at most 8): channels R, G, B
  // (radiance, including the background, emission and obstacles) and A (alpha = 1 − T of the camera ray; 1
  // where it meets an obstacle). `obstacles`, placed for the frame (ObstacleBvh::update), are opaque
  // Lambertian surfaces of the real-time pass's albedo (kObstacleAlbedo); none when null or empty.
  void beginImage(const render::Volume& volume, const scene::Smoke& smoke, const render::Camera& camera,
                  const render::ImagePlane& plane, const std::vector<scene::Light>& lights,
                  const TraceSettings& settings, const render::ObstacleBvh* obstacles = nullptr);
  // Starts six-way lightmaps: the eight channels of sixway.h, each light channel lit by one white
  // directional light of irradiance π from its camera-relative direction (or settings.sixWayLights), black
  // world; emissive is the
  // emission seen directly. Background and environment are not used.
  void beginSixWay(const render::Volume& volume, const scene::Smoke& smoke, const render::Camera& camera,
                   const render::ImagePlane& billboard, const TraceSettings& settings);

  // Adds `samplesPerPixel` samples (rounded up to whole passes).
  void accumulate(uint32_t samplesPerPixel);
  uint32_t samples() const { return samples_; }
  // The mean of the samples so far.
  io::Image image() const;
  // GPU milliseconds spent tracing since begin (GPU timestamps of the passes).
  double traceMilliseconds() const { return traceMs_; }

 private:
  void begin(const render::Volume& volume, const scene::Smoke& smoke, const render::Camera& camera,
             const render::ImagePlane& plane, const TraceSettings& settings, bool sixWay);

  const gpu::Context* context_;
  std::unique_ptr<render::BrickMajorantPass> majorantPass_;
  std::unique_ptr<gpu::Pipeline> imagePass_, sixWayPass_;
  gpu::Buffer params_, majorants_, accumulation_, readback_;
  gpu::Buffer noObstacles_;  // bound in place of the obstacle buffers when there are none
  const render::ObstacleBvh* obstacles_ = nullptr;
  render::RecordedSequence prepare_, trace_;
  mutable render::RecordedSequence read_;
  std::vector<uint64_t> traceKey_;
  std::vector<std::string> channels_;
  TraceSettings settings_;
  uint32_t samples_ = 0;
  double traceMs_ = 0;
  bool sixWay_ = false;
  render::Volume volume_;
};

}  // namespace sixway::reference
