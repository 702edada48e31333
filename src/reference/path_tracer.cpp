#include "reference/path_tracer.h"

#include <algorithm>
#include <glm/geometric.hpp>
#include <numbers>
#include <string>
#include <variant>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "io/error.h"
#include "render/gpu_layout.h"
#include "render/obstacle_pass.h"
#include "render/render_spec.h"
#include "render/sixway.h"

namespace sixway::reference {
namespace {

uint32_t groups(int count, int groupSize) {
  return uint32_t((count + groupSize - 1) / groupSize);
}

void checkSettings(const TraceSettings& s, size_t lights) {
  auto fail = [](const std::string& problem) { throw io::InputError("path tracer", problem); };
  if (s.width < 1 || s.height < 1 || s.width > 16384 || s.height > 16384)
    fail("image size " + std::to_string(s.width) + "x" + std::to_string(s.height) + " is outside 1..16384");
  if (s.maxOrders < 0) fail("the number of scattering orders must be >= 0");
  if (s.minOrder < 1) fail("the lowest recorded scattering order must be >= 1");
  if (s.samplesPerPass < 1 || s.samplesPerPass > 4096) fail("samples per pass must be in 1..4096");
  if (s.brickCells < 1 || s.brickCells > 64) fail("majorant bricks must be 1..64 cells wide");
  if (lights > size_t(render::layout::kMaxLights))
    fail(std::to_string(lights) + " lights; at most " + std::to_string(render::layout::kMaxLights));
}

// w of the radiance: 1 where obstacles cast shadows from the light.
render::layout::PathLight pathLight(const scene::Light& light) {
  const glm::vec4 radiance(light.color * light.intensity, light.shadows ? 1.0f : 0.0f);
  if (const auto* directional = std::get_if<scene::DirectionalLight>(&light.source))
    return {glm::vec4(directional->direction, 0.0f), radiance};
  return {glm::vec4(std::get<scene::PointLight>(light.source).position, 1.0f), radiance};
}

}  // namespace

PathTracer::PathTracer(const gpu::Context& context, const gpu::PipelineCache& cache)
    : context_(&context),
      params_(context, sizeof(render::layout::TraceParams), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
              gpu::MemoryKind::HostUpload, "path tracer parameters"),
      prepare_(context),
      trace_(context),
      read_(context) {
  using gpu::BindingType;
  majorantPass_ = std::make_unique<render::BrickMajorantPass>(context, cache);
  const std::vector<BindingType> bindings = {BindingType::UniformBuffer, BindingType::StorageBuffer,
                                             BindingType::StorageBuffer, BindingType::StorageBuffer,
                                             BindingType::StorageBuffer, BindingType::StorageBuffer,
                                             BindingType::StorageBuffer, BindingType::StorageBuffer};
  gpu::ComputePipelineDesc desc{"render/path_trace.comp", bindings, 0};
  desc.spec.set(render::spec::kSixWay, false);
  imagePass_ = std::make_unique<gpu::Pipeline>(context, cache, desc);
  desc.spec = gpu::SpecConstants().set(render::spec::kSixWay, true);
  sixWayPass_ = std::make_unique<gpu::Pipeline>(context, cache, desc);
  noObstacles_ = gpu::Buffer::storage(context, sizeof(render::BvhTriangle), "no obstacles");
}

PathTracer::~PathTracer() = default;

void PathTracer::beginImage(const render::Volume& volume, const scene::Smoke& smoke,
                            const render::Camera& camera, const render::ImagePlane& plane,
                            const std::vector<scene::Light>& lights, const TraceSettings& settings,
                            const render::ObstacleBvh* obstacles) {
  checkSettings(settings, lights.size());
  render::layout::TraceParams& p = *static_cast<render::layout::TraceParams*>(params_.mapped());
  p = {};
  for (size_t i = 0; i < lights.size(); ++i) p.lights[i] = pathLight(lights[i]);
  p.image.w = int(lights.size());
  p.background = glm::vec4(settings.background, 0.0f);
  obstacles_ = obstacles && obstacles->obstacleCount() > 0 ? obstacles : nullptr;
  // Rays leave a surface this far along its normal (1e-5 of the volume's diagonal, about a hundred times
  // float rounding there): they must not find the surface they left.
  p.obstacles = glm::vec4(obstacles_ ? float(obstacles_->obstacleCount()) : 0.0f, render::kObstacleAlbedo.x,
                          1e-5f * glm::length(volume.grid.bounds().size()), 0.0f);
  for (int i = 0; i < 4; ++i) p.environment[i] = glm::vec4(settings.environment[i], 0.0f);
  channels_ = {"R", "G", "B", "A"};
  begin(volume, smoke, camera, plane, settings, false);
}

void PathTracer::beginSixWay(const render::Volume& volume, const scene::Smoke& smoke,
                             const render::Camera& camera, const render::ImagePlane& billboard,
                             const TraceSettings& settings) {
  checkSettings(settings, render::kSixWayLights);
  render::layout::TraceParams& p = *static_cast<render::layout::TraceParams*>(params_.mapped());
  p = {};
  obstacles_ = nullptr;
  const auto directions = settings.sixWayLights.value_or(render::sixWayLightDirections(camera));
  for (int i = 0; i < render::kSixWayLights; ++i)
    p.lights[i] = {glm::vec4(directions[i], 0.0f), glm::vec4(glm::vec3(std::numbers::pi_v<float>), float(i))};
  p.image.w = render::kSixWayLights;
  channels_ = {render::sixWayChannelNames().begin(), render::sixWayChannelNames().end()};
  begin(volume, smoke, camera, billboard, settings, true);
}

void PathTracer::begin(const render::Volume& volume, const scene::Smoke& smoke, const render::Camera& camera,
                       const render::ImagePlane& plane, const TraceSettings& settings, bool sixWay) {
  render::requireConsistent(volume);
  settings_ = settings;
  sixWay_ = sixWay;
  volume_ = volume;
  samples_ = 0;
  traceMs_ = 0;
  const glm::ivec3 bricks = (volume.grid.size + settings.brickCells - 1) / settings.brickCells;
  const uint64_t brickCount = uint64_t(bricks.x) * bricks.y * bricks.z;
  const uint64_t values = channels_.size() * uint64_t(settings.width) * settings.height;
  if (majorants_.size() < brickCount * sizeof(float))
    majorants_ = gpu::Buffer::storage(*context_, brickCount * sizeof(float), "majorant bricks");
  if (accumulation_.size() < values * sizeof(float)) {
    accumulation_ = gpu::Buffer::storage(*context_, values * sizeof(float), "path tracer sums");
    readback_ = gpu::Buffer(*context_, values * sizeof(float), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                            gpu::MemoryKind::HostReadback, "path tracer sums (readback)");
  }

  render::layout::TraceParams& p = *static_cast<render::layout::TraceParams*>(params_.mapped());
  p.volume = render::layout::volumeGrid(volume.grid);
  p.camera = render::layout::cameraRays(camera, plane);
  p.optics = glm::vec4(smoke.extinction, smoke.albedo, smoke.phaseG, smoke.emission.intensity);
  p.bricks = glm::ivec4(bricks, settings.brickCells);
  p.frame = glm::uvec4(settings.seed, 0u, uint32_t(settings.samplesPerPass), uint32_t(settings.maxOrders));
  p.image.x = settings.width;
  p.image.y = settings.height;
  p.image.z = render::layout::emissionRamp(smoke.emission, p.ramp);
  p.flags =
      glm::uvec4(settings.jitter ? 1u : 0u, volume.temperature ? 1u : 0u, uint32_t(settings.minOrder), 0u);

  const gpu::Buffer& density = *volume.density;
  prepare_
      .get({render::handleKey(density.handle()), render::handleKey(majorants_.handle()),
            render::handleKey(accumulation_.handle()), uint64_t(volume.grid.size.x),
            uint64_t(volume.grid.size.y), uint64_t(volume.grid.size.z), uint64_t(settings.brickCells)},
           [&](gpu::Sequence& s) {
             s.fill(accumulation_, 0u);
             majorantPass_->record(s, volume, settings.brickCells, majorants_);
           })
      .submit();
  const gpu::Buffer& temperature = volume.temperature ? *volume.temperature : density;
  traceKey_ = {render::handleKey(density.handle()),
               render::handleKey(temperature.handle()),
               render::handleKey(majorants_.handle()),
               render::handleKey(accumulation_.handle()),
               uint64_t(settings.width),
               uint64_t(settings.height),
               uint64_t(sixWay),
               render::handleKey((obstacles_ ? obstacles_->nodes() : noObstacles_).handle()),
               render::handleKey((obstacles_ ? obstacles_->triangles() : noObstacles_).handle()),
               render::handleKey((obstacles_ ? obstacles_->placements() : noObstacles_).handle())};
}

void PathTracer::accumulate(uint32_t samplesPerPixel) {
  if (!volume_.density) throw std::logic_error("PathTracer::accumulate before begin");
  render::layout::TraceParams& p = *static_cast<render::layout::TraceParams*>(params_.mapped());
  const gpu::Buffer& density = *volume_.density;
  const gpu::Buffer& temperature = volume_.temperature ? *volume_.temperature : density;
  const gpu::Buffer& nodes = obstacles_ ? obstacles_->nodes() : noObstacles_;
  const gpu::Buffer& triangles = obstacles_ ? obstacles_->triangles() : noObstacles_;
  const gpu::Buffer& placements = obstacles_ ? obstacles_->placements() : noObstacles_;
  gpu::Sequence& pass = trace_.get(traceKey_, [&](gpu::Sequence& s) {
    s.beginStage("path trace");
    s.dispatch(
        sixWay_ ? *sixWayPass_ : *imagePass_,
        {gpu::reads(params_), gpu::reads(density), gpu::reads(temperature), gpu::reads(majorants_),
         gpu::readsWrites(accumulation_), gpu::reads(nodes), gpu::reads(triangles), gpu::reads(placements)},
        std::span<const std::byte>(), groups(settings_.width, 8), groups(settings_.height, 8));
    s.endStage();
  });
  for (uint32_t done = 0; done < samplesPerPixel; done += uint32_t(settings_.samplesPerPass)) {
    p.frame.y = samples_;
    pass.submit();
    samples_ += uint32_t(settings_.samplesPerPass);
    if (!pass.stageTimes().empty()) traceMs_ += pass.stageTimes().front().milliseconds;
  }
}

io::Image PathTracer::image() const {
  io::Image image(settings_.width, settings_.height, channels_);
  if (samples_ == 0) return image;
  read_
      .get({render::handleKey(accumulation_.handle())},
           [&](gpu::Sequence& s) { s.copy(accumulation_, readback_); })
      .submit();
  const auto* sums = static_cast<const float*>(readback_.mapped());
  const uint64_t plane = uint64_t(settings_.width) * settings_.height;
  const size_t channels = channels_.size();
  for (uint64_t i = 0; i < plane; ++i)
    for (size_t c = 0; c < channels; ++c)
      image.pixels[i * channels + c] = sums[c * plane + i] / float(samples_);
  return image;
}

}  // namespace sixway::reference
