#include "render/guiding_map.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>
#include <string>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "io/error.h"
#include "render/gpu_layout.h"
#include "render/render_spec.h"

namespace sixway::render {
namespace {

// A ray stops once less than this of the background shows through (and its shell depth is known): what it
// leaves out is below the fp16 rounding of alpha near 1 (2^−11).
constexpr float kStopTransmittance = 1e-3f;
constexpr int kMaxGrids = 3;  // guide_march.comp's light-grid bindings: one per axis of the six-way frame

struct GuideFrame {  // guide_march.comp
  glm::uvec4 jitter;
  glm::vec4 shell;
};

uint32_t groups(int count, int groupSize) {
  return uint32_t((count + groupSize - 1) / groupSize);
}

std::string text(float value) {
  std::string s = std::to_string(value);
  s.erase(s.find_last_not_of('0') + 1);
  if (s.back() == '.') s.pop_back();
  return s;
}

void checkSettings(const GuideSettings& s) {
  const auto fail = [](const std::string& problem) { throw io::InputError("guiding map", problem); };
  if (s.size < 1 || s.size > 16384) fail("size " + std::to_string(s.size) + " is outside 1..16384");
  if (!(s.stepCells > 0.0f && std::isfinite(s.stepCells)))
    fail("the step must be > 0 cells (got " + text(s.stepCells) + ")");
  if (!(s.shadowSpacingCells > 0.0f && std::isfinite(s.shadowSpacingCells)))
    fail("the light grid spacing must be > 0 cells (got " + text(s.shadowSpacingCells) + ")");
  if (s.lights.empty()) fail("needs at least one light");
  for (size_t i = 0; i < s.lights.size(); ++i)
    if (std::count(s.lights.begin(), s.lights.end(), s.lights[i]) > 1) fail("lists a light twice");
  if (!(s.shellThreshold > 0.0f && s.shellThreshold < 1.0f))
    fail("the shell threshold must be in (0, 1) (got " + text(s.shellThreshold) + ")");
  if (!(s.alphaStepCells >= 0.0f && std::isfinite(s.alphaStepCells)))
    fail("the fine alpha step must be >= 0 cells (got " + text(s.alphaStepCells) + ")");
  if (s.emission && s.alphaStepCells <= 0.0f)
    fail("the emission needs the fine march (a fine alpha step > 0)");
}

// The axis of the six-way frame a light lies on: opposite lights share a light grid.
int axisOf(scene::GuideLight light) {
  switch (light) {
    case scene::GuideLight::Right:
    case scene::GuideLight::Left:
      return 0;
    case scene::GuideLight::Top:
    case scene::GuideLight::Bottom:
      return 1;
    default:
      return 2;
  }
}

// Toward the light, in the camera-relative six-way frame (docs/conventions.md, "Six-way frame"), with the two
// axes across it that the baker's grid for the same light uses.
struct LightFrame {
  glm::vec3 toLight, u, v;
};
LightFrame lightFrame(scene::GuideLight light, const Camera& c) {
  switch (light) {
    case scene::GuideLight::Right:
      return {c.right, c.up, c.forward};
    case scene::GuideLight::Left:
      return {-c.right, c.up, c.forward};
    case scene::GuideLight::Top:
      return {c.up, c.right, c.forward};
    case scene::GuideLight::Bottom:
      return {-c.up, c.right, c.forward};
    case scene::GuideLight::Back:
      return {c.forward, c.right, c.up};
    case scene::GuideLight::Front:
      break;
  }
  return {-c.forward, c.right, c.up};
}

}  // namespace

GuideSettings GuideSettings::fromScene(const scene::Scene& scene) {
  GuideSettings s;
  s.size = uint32_t(scene.render.lightmapSize);
  s.stepCells = scene.render.guideStepVoxels;
  s.alphaStepCells = scene.render.guideAlphaStepVoxels;
  s.lights = scene.render.guideLights;
  s.shellThreshold = scene.render.shellThreshold;
  s.seed = scene.render.seed;
  return s;
}

GuidingMap::GuidingMap(const gpu::Context& context, const gpu::PipelineCache& cache,
                       const GuideSettings& settings)
    : context_(&context),
      settings_(settings),
      // A storage buffer for guide_march.comp, a uniform block for light_depth.comp (render/gpu_layout.h).
      params_(context, sizeof(layout::BakeParams),
              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
              gpu::MemoryKind::FrameParameters, "guide parameters"),
      frame_(context, sizeof(GuideFrame), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
             gpu::MemoryKind::FrameParameters, "guide frame"),
      noEmission_(context, {1, 1, 1, VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT, "no guide emission"}) {
  checkSettings(settings_);
  opacityDepths_ = gpu::Image(
      context, {settings.size, settings.size, 1, VK_FORMAT_R16G16B16A16_SFLOAT,
                VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                "guide opacity depths"});
  // One light grid per axis of the six-way frame that a guide light other than front lies on; the shader's
  // kLightGrids holds, per such light k, its grid (bits 3k, 3k + 1) and whether it is the grid's opposite.
  int32_t lightGrids = 0, shadowed = 0;
  for (scene::GuideLight light : settings_.lights) {
    if (light == scene::GuideLight::Front) continue;
    const size_t grid = std::find_if(gridLights_.begin(), gridLights_.end(),
                                     [&](scene::GuideLight l) { return axisOf(l) == axisOf(light); }) -
                        gridLights_.begin();
    if (grid == gridLights_.size()) gridLights_.push_back(light);
    lightGrids |= int32_t(grid | (gridLights_[grid] != light ? 4 : 0)) << (3 * shadowed++);
  }
  using gpu::BindingType;
  majorantPass_ = std::make_unique<BrickMajorantPass>(context, cache);
  depthPass_ = lightDepthPipeline(context, cache);
  // guide_march.comp's bindings: parameters, frame, density, bricks, the light grids, the guide, temperature,
  // the emission, the opacity depths.
  std::vector<BindingType> march(4 + kMaxGrids + 4, BindingType::StorageBuffer);
  march[4 + kMaxGrids] = march[4 + kMaxGrids + 2] = march.back() = BindingType::StorageImage;
  gpu::SpecConstants constants;
  constants.set(spec::kShadowedLights, shadowed);
  constants.set(spec::kFrontLight, size_t(shadowed) < settings_.lights.size());
  constants.set(spec::kLightGrids, lightGrids);
  constants.set(spec::kFineAlpha, settings_.alphaStepCells > 0.0f);
  constants.set(spec::kEmission, settings_.emission);
  marchPass_ = std::make_unique<gpu::Pipeline>(
      context, cache, gpu::ComputePipelineDesc{"render/guide_march.comp", march, 0, constants});
}

GuidingMap::~GuidingMap() = default;

gpu::ImageDesc GuidingMap::imageDesc() const {
  return {settings_.size,
          settings_.size,
          1,
          VK_FORMAT_R16G16B16A16_SFLOAT,
          VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
          "guiding map"};
}

gpu::ImageDesc GuidingMap::emissionDesc() const {
  return {settings_.size,
          settings_.size,
          1,
          VK_FORMAT_R32_SFLOAT,
          VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
          "guide emission"};
}

void GuidingMap::record(gpu::Sequence& sequence, const Volume& volume, const gpu::Image& guide,
                        const gpu::Image* emission) {
  requireConsistent(volume);
  const gpu::ImageDesc& d = guide.desc();
  if (d.width != settings_.size || d.height != settings_.size || d.depth != 1 ||
      d.format != VK_FORMAT_R16G16B16A16_SFLOAT)
    throw std::invalid_argument("guiding map: the image must be RGBA16F, " + std::to_string(settings_.size) +
                                " pixels square");
  if (settings_.emission != (emission != nullptr))
    throw std::invalid_argument(settings_.emission
                                    ? "guiding map: the settings ask for an emission image"
                                    : "guiding map: an emission image without settings.emission");
  if (emission && (emission->desc().width != settings_.size || emission->desc().height != settings_.size ||
                   emission->desc().depth != 1 || emission->desc().format != VK_FORMAT_R32_SFLOAT))
    throw std::invalid_argument("guiding map: the emission image must be R32F, " +
                                std::to_string(settings_.size) + " pixels square");
  // Every light grid of this lattice, whatever the camera, spans at most the box's diagonal (plus one node
  // of alignment on each side): a fixed capacity, so that the dispatches do not depend on the camera.
  grid_ = volume.grid;
  temperature_ = volume.temperature != nullptr;
  const float diagonal = glm::length(grid_.bounds().size());
  const auto nodesFor = [&](float spacing) { return lightGridAxisNodes(std::ceil(diagonal / spacing)) + 2; };
  const auto bytesFor = [](int nodes) { return uint64_t(nodes) * uint64_t(nodes) * uint64_t(nodes) * 4; };
  spacing_ = widenedSpacing(settings_.shadowSpacingCells * grid_.cellSize, [&](float spacing) {
    const uint64_t bytes = bytesFor(nodesFor(spacing));
    return bytes <= context_->limits().maxStorageBufferRange &&
           bytes * std::max<size_t>(1, gridLights_.size()) <=
               context_->capabilities().deviceLocalHeapBytes / 8;
  });
  gridNodes_ = nodesFor(spacing_);
  // Kept when a recording for a lattice of the same size finds them (every frame writes them before reading):
  // frames an engine has in flight may still run an earlier recording that reads them.
  const uint64_t depthBytes = gridLights_.empty() ? sizeof(float) : bytesFor(gridNodes_);
  const size_t depthGrids = std::max<size_t>(1, gridLights_.size());
  if (depths_.size() != depthGrids || depths_.front().size() != depthBytes) {
    depths_.clear();
    for (size_t i = 0; i < depthGrids; ++i)
      depths_.push_back(gpu::Buffer::storage(*context_, depthBytes, "guide light grid " + std::to_string(i)));
  }
  const glm::ivec3 bricks = (grid_.size + kBrickCells - 1) / kBrickCells;
  const uint64_t brickBytes = uint64_t(bricks.x) * bricks.y * bricks.z * sizeof(float);
  if (bricks_.size() != brickBytes)
    bricks_ = gpu::Buffer::storage(*context_, brickBytes, "guide empty-space bricks");

  const gpu::Buffer& density = *volume.density;
  sequence.beginStage("guide");
  majorantPass_->record(sequence, volume, kBrickCells, bricks_);
  for (uint32_t light = 0; light < gridLights_.size(); ++light)
    sequence.dispatch(
        *depthPass_,
        {gpu::reads(params_), gpu::reads(density), gpu::reads(bricks_), gpu::writes(depths_[light])}, light,
        groups(gridNodes_, 8), groups(gridNodes_, 8));
  std::vector<gpu::Binding> bindings = {gpu::reads(params_), gpu::reads(frame_), gpu::reads(density),
                                        gpu::reads(bricks_)};
  for (int i = 0; i < kMaxGrids; ++i)
    bindings.push_back(gpu::reads(depths_[std::min<size_t>(i, depths_.size() - 1)]));
  bindings.push_back(gpu::writes(guide));
  bindings.push_back(gpu::reads(volume.temperature ? *volume.temperature : density));  // unread without one
  bindings.push_back(gpu::writes(emission ? *emission : noEmission_));
  bindings.push_back(gpu::writes(opacityDepths_));
  sequence.dispatch(*marchPass_, bindings, std::span<const std::byte>(), groups(int(settings_.size), 8),
                    groups(int(settings_.size), 8));
  sequence.endStage();
}

void GuidingMap::update(const Camera& camera, const ImagePlane& billboard, const DepthRange& shellRange,
                        const scene::Smoke& smoke, uint32_t frame) {
  if (gridNodes_ == 0) throw std::logic_error("GuidingMap::update before record");
  // One midpoint sample per interval of a column (finer ones change the result by far less than the
  // interpolation between columns); the step limit sits a hair above the interval so that rounding cannot
  // make it two steps on one side only.
  const float columnStep = spacing_ * 1.001f;
  grids_.clear();
  for (scene::GuideLight light : gridLights_) {
    const LightFrame f = lightFrame(light, camera);
    grids_.push_back(lightGridFor(grid_, f.toLight, f.u, f.v, spacing_, columnStep));
    if (glm::any(glm::greaterThan(grids_.back().nodes, glm::ivec3(gridNodes_))))
      throw std::logic_error("guiding map: a light grid outgrew its capacity");
  }

  layout::BakeParams p{};
  p.volume = layout::volumeGrid(grid_);
  p.camera = layout::cameraRays(camera, billboard);
  p.optics = glm::vec4(smoke.extinction, smoke.albedo, smoke.phaseG, smoke.emission.intensity);
  p.march = glm::vec4(settings_.stepCells * grid_.cellSize, kStopTransmittance,
                      settings_.alphaStepCells * grid_.cellSize, 0.0f);
  const int rampKeys = settings_.emission ? layout::emissionRamp(smoke.emission, p.ramp) : 0;
  p.image = glm::ivec4(int(settings_.size), int(settings_.size), rampKeys, temperature_ ? 1 : 0);
  p.bricks = glm::ivec4((grid_.size + kBrickCells - 1) / kBrickCells, kBrickCells);
  for (size_t i = 0; i < grids_.size(); ++i) p.lights[i] = layout::lightGrid(grids_[i]);
  params_.upload(std::as_bytes(std::span(&p, 1)));
  const GuideFrame f{glm::uvec4(settings_.seed, frame, 0u, 0u),
                     glm::vec4(settings_.shellThreshold, shellRange.near, shellRange.far, 0.0f)};
  frame_.upload(std::as_bytes(std::span(&f, 1)));
}

}  // namespace sixway::render
