#include "reference/lightmap_baker.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <string>
#include <utility>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "io/error.h"
#include "render/gpu_layout.h"
#include "render/sixway.h"

namespace sixway::reference {
namespace {

uint32_t groups(int count, int groupSize) {
  return uint32_t((count + groupSize - 1) / groupSize);
}

void checkSettings(const BakeSettings& s) {
  if (s.width < 1 || s.height < 1 || s.width > 16384 || s.height > 16384)
    throw io::InputError("bake", "lightmap size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                                     " is outside 1..16384");
  if (!(s.stepCells > 0.0f && s.stepCells <= 0.5f))
    throw io::InputError(
        "bake", "the march step must be in (0, 0.5] cells (got " + std::to_string(s.stepCells) + ")");
  if (!(s.lightSpacingCells > 0.0f)) throw io::InputError("bake", "the light grid spacing must be > 0 cells");
  if (!(s.minTransmittance >= 0.0f && s.minTransmittance < 1.0f))
    throw io::InputError("bake", "the transmittance cut-off must be in [0, 1)");
  if (s.lights)
    for (const glm::vec3& d : *s.lights)
      if (!(std::abs(glm::length(d) - 1.0f) < 1e-4f))
        throw std::invalid_argument("bake: a light direction is not a unit vector");
}

}  // namespace

float lightSpacingFor(float cellOpticalDepth) {
  return cellOpticalDepth > 0.5f ? std::max(0.25f, 0.5f / cellOpticalDepth) : 1.0f;
}

namespace {

// Two unit axes across the unit direction `d`, orthogonal to it and to each other.
std::pair<glm::vec3, glm::vec3> axesAcross(glm::vec3 d) {
  const glm::vec3 a = glm::abs(d);
  const glm::vec3 least = a.x <= a.y && a.x <= a.z ? glm::vec3(1, 0, 0)
                          : a.y <= a.z             ? glm::vec3(0, 1, 0)
                                                   : glm::vec3(0, 0, 1);
  const glm::vec3 u = glm::normalize(glm::cross(d, least));
  return {u, glm::cross(d, u)};
}

// Light grids for the six lights, their columns spaced `spacing` apart; across the camera's axis lights u, v
// are the other two camera axes.
std::array<render::LightGrid, 6> sixLightGrids(const render::Camera& camera, const render::VolumeGrid& volume,
                                               const BakeSettings& settings, float spacing, float maxStep) {
  const auto directions = settings.lights.value_or(render::sixWayLightDirections(camera));
  std::array<render::LightGrid, 6> grids;
  for (int i = 0; i < render::kSixWayLights; ++i) {
    auto [u, v] = axesAcross(directions[i]);
    if (!settings.lights) {
      const int axis = i / 2;  // 0: right/left, 1: top/bottom, 2: back/front
      u = axis == 0 ? camera.up : camera.right;
      v = axis == 2 ? camera.up : camera.forward;
    }
    grids[i] = render::lightGridFor(volume, directions[i], u, v, spacing, maxStep);
  }
  return grids;
}

// Whether the six light grids fit: each in one storage buffer, all together in a quarter of the device's
// memory.
bool fits(const std::array<render::LightGrid, 6>& grids, const gpu::Context& context) {
  uint64_t largest = 0, total = 0;
  for (const render::LightGrid& g : grids) {
    largest = std::max(largest, g.nodeCount() * sizeof(float));
    total += g.nodeCount() * sizeof(float);
  }
  return largest <= context.limits().maxStorageBufferRange &&
         total <= context.capabilities().deviceLocalHeapBytes / 4;
}

}  // namespace

LightmapBaker::LightmapBaker(const gpu::Context& context, const gpu::PipelineCache& cache)
    : context_(&context),
      params_(context, sizeof(render::layout::BakeParams),
              VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
              gpu::MemoryKind::HostUpload, "bake parameters"),
      sequence_(context) {
  using gpu::BindingType;
  majorantPass_ = std::make_unique<render::BrickMajorantPass>(context, cache);
  depthPass_ = render::lightDepthPipeline(context, cache);
  // Its parameters too, as a storage buffer: bake_params.glsl.
  const std::vector<BindingType> march(11, BindingType::StorageBuffer);
  marchPass_ = std::make_unique<gpu::Pipeline>(
      context, cache, gpu::ComputePipelineDesc{"render/sixway_march.comp", march, 0});
}

LightmapBaker::~LightmapBaker() = default;

void LightmapBaker::ensureCapacity(const render::VolumeGrid& grid, uint64_t lightmapValues) {
  const auto& names = render::sixWayChannelNames();
  for (int i = 0; i < render::kSixWayLights; ++i) {
    const uint64_t bytes = grids_[i].nodeCount() * sizeof(float);
    if (depths_[i].size() < bytes)
      depths_[i] = gpu::Buffer::storage(*context_, bytes, "optical depths toward the " + names[i] + " light");
  }
  const uint64_t brickBytes = render::BrickMajorantPass::bufferBytes(grid, kBrickCells);
  if (bricks_.size() < brickBytes)
    bricks_ = gpu::Buffer::storage(*context_, brickBytes, "empty-space bricks");
  if (lightmaps_.size() < lightmapValues * sizeof(float)) {
    lightmaps_ = gpu::Buffer::storage(*context_, lightmapValues * sizeof(float), "six-way lightmaps");
    readback_ = gpu::Buffer(*context_, lightmapValues * sizeof(float), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                            gpu::MemoryKind::HostReadback, "six-way lightmaps (readback)");
  }
}

io::Image LightmapBaker::bake(const render::Volume& volume, const scene::Smoke& smoke,
                              const render::Camera& camera, const render::ImagePlane& billboard,
                              const BakeSettings& settings) {
  checkSettings(settings);
  render::requireConsistent(volume);
  const float cell = volume.grid.cellSize;
  const float maxStep = settings.stepCells * cell;
  // Widen the light grids' spacing until they fit the device.
  const float spacing = render::widenedSpacing(settings.lightSpacingCells * cell, [&](float s) {
    return fits(sixLightGrids(camera, volume.grid, settings, s, maxStep), *context_);
  });
  grids_ = sixLightGrids(camera, volume.grid, settings, spacing, maxStep);
  const uint64_t plane = uint64_t(settings.width) * uint64_t(settings.height);
  ensureCapacity(volume.grid, render::kSixWayChannels * plane);
  const glm::ivec3 bricks = (volume.grid.size + kBrickCells - 1) / kBrickCells;

  render::layout::BakeParams p{};
  p.volume = render::layout::volumeGrid(volume.grid);
  p.camera = render::layout::cameraRays(camera, billboard);
  p.optics = glm::vec4(smoke.extinction, smoke.albedo, smoke.phaseG, smoke.emission.intensity);
  p.march = glm::vec4(maxStep, settings.minTransmittance, 0.0f, 0.0f);
  const int rampKeys = render::layout::emissionRamp(smoke.emission, p.ramp);
  p.image = glm::ivec4(settings.width, settings.height, rampKeys, volume.temperature ? 1 : 0);
  p.bricks = glm::ivec4(bricks, kBrickCells);
  for (int i = 0; i < render::kSixWayLights; ++i) p.lights[i] = render::layout::lightGrid(grids_[i]);
  params_.upload(std::as_bytes(std::span(&p, 1)));

  const gpu::Buffer& density = *volume.density;
  const gpu::Buffer& temperature = volume.temperature ? *volume.temperature : density;
  std::vector<uint64_t> key = {render::handleKey(density.handle()),
                               render::handleKey(temperature.handle()),
                               render::handleKey(bricks_.handle()),
                               render::handleKey(lightmaps_.handle()),
                               uint64_t(settings.width),
                               uint64_t(settings.height),
                               uint64_t(volume.grid.size.x),
                               uint64_t(volume.grid.size.y),
                               uint64_t(volume.grid.size.z)};
  for (int i = 0; i < render::kSixWayLights; ++i)
    key.insert(key.end(), {render::handleKey(depths_[i].handle()), uint64_t(grids_[i].nodes.x),
                           uint64_t(grids_[i].nodes.y)});
  last_ = &sequence_.get(key, [&](gpu::Sequence& s) {
    s.beginStage("empty-space bricks");
    majorantPass_->record(s, volume, kBrickCells, bricks_);
    s.endStage();
    s.beginStage("light depth");
    for (uint32_t light = 0; light < render::kSixWayLights; ++light)
      s.dispatch(*depthPass_,
                 {gpu::reads(params_), gpu::reads(density), gpu::reads(bricks_), gpu::writes(depths_[light])},
                 light, groups(grids_[light].nodes.x, 8), groups(grids_[light].nodes.y, 8));
    s.endStage();
    s.beginStage("view march");
    std::vector<gpu::Binding> bindings = {gpu::reads(params_), gpu::reads(density), gpu::reads(temperature),
                                          gpu::reads(bricks_)};
    for (const gpu::Buffer& d : depths_) bindings.push_back(gpu::reads(d));
    bindings.push_back(gpu::writes(lightmaps_));
    s.dispatch(*marchPass_, bindings, std::span<const std::byte>(), groups(settings.width, 8),
               groups(settings.height, 8));
    s.endStage();
    s.copy(lightmaps_, readback_);
  });
  last_->submit();

  // Channel-planar on the GPU, interleaved in the image.
  const auto* values = static_cast<const float*>(readback_.mapped());
  io::Image image(settings.width, settings.height,
                  {render::sixWayChannelNames().begin(), render::sixWayChannelNames().end()});
  for (uint64_t i = 0; i < plane; ++i)
    for (int c = 0; c < render::kSixWayChannels; ++c)
      image.pixels[i * render::kSixWayChannels + c] = values[c * plane + i];
  return image;
}

const std::vector<gpu::StageTime>& LightmapBaker::stageTimes() const {
  static const std::vector<gpu::StageTime> none;
  return last_ ? last_->stageTimes() : none;
}

std::vector<float> LightmapBaker::lightDepths(int light) const {
  std::vector<float> values(grids_[light].nodeCount());
  depths_[light].download(std::as_writable_bytes(std::span(values)));
  return values;
}

}  // namespace sixway::reference
