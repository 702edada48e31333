#include <sixway/smoke_renderer.h>

#include <algorithm>
#include <glm/gtc/packing.hpp>
#include <stdexcept>

#include "gpu/image.h"
#include "render/scene_frame.h"
#include "render/shadow_maps.h"
#include "runtime/internal.h"
#include "runtime/network_lightmaps.h"
#include "runtime/scene_lights.h"
#include "runtime/smoke_renderer_impl.h"

namespace sixway {
namespace {

runtime::FrameTarget frameTarget(const gpu::Context& context, const scene::Scene& scene,
                                 const RenderTarget* target) {
  if (!target) return {uint32_t(scene.render.width), uint32_t(scene.render.height), {}, {}};
  if (!target->colorImage || !target->colorView || !target->depthImage || !target->depthView ||
      target->width == 0 || target->height == 0)
    throw std::invalid_argument("RenderTarget: colour and depth images, views and a size are needed");
  if (!gpu::isDepthFormat(target->depthFormat))
    throw std::invalid_argument("RenderTarget: depth format " + std::to_string(target->depthFormat) +
                                " is not D16, D24 or D32 (with or without stencil)");
  return {target->width, target->height,
          gpu::Image::borrowed(context, target->colorImage, target->colorView,
                               {target->width, target->height, 1, target->colorFormat,
                                VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "engine colour"}),
          gpu::Image::borrowed(context, target->depthImage, target->depthView,
                               {target->width, target->height, 1, target->depthFormat,
                                VK_IMAGE_USAGE_SAMPLED_BIT, "engine depth"})};
}

uint32_t shadowTiles(const scene::Scene& scene, const RendererOptions& options) {
  if (!options.shadows) return 0;
  return options.shadowedLights ? *options.shadowedLights
                                : render::shadowTileCount(scene.lights, scene.obstacles);
}

}  // namespace

SmokeRenderer::Impl::Impl(const gpu::Context& context, const gpu::PipelineCache& cache,
                          const SmokeSimulation& simulation, const RendererOptions& options,
                          const RenderTarget* target)
    : simulation(simulation),
      scene(runtime::Access::scene(simulation)),
      engineTarget(target != nullptr),
      renderer(
          context, cache, scene, frameTarget(context, scene, target), shadowTiles(scene, options),
          std::make_unique<runtime::NetworkLightmaps>(context, cache, scene, options.weights, options.fp16)) {
}

gpu::Sequence& SmokeRenderer::Impl::prepare() {
  const runtime::SimulatedVolumes& volumes = runtime::Access::volumes(simulation);
  const sim::Simulation& sim = volumes.simulation();
  for (size_t o = 0; o < scene.obstacles.size(); ++o)
    renderer.frame().meshes().setMotion(o, sim.obstacleMotion(o));
  // The smoke after `frames` frames is frame frames − 1.
  const int index = std::max(0, simulation.framesSimulated() - 1);
  runtime::FrameInput input{volumes.currentVolume(),
                            runtime::Access::starts(simulation),
                            {view ? view->camera : render::sceneCamera(scene.camera, index),
                             lights ? *lights : render::sceneLights(scene.lights, index)},
                            index,
                            sim.seconds()};
  // A restarted simulation may reuse a handle value: the start count tells its volume apart. An engine's
  // depth buffer holds its projection's depth; sixway's own, the obstacle pass's.
  if (view) input.plane = view->plane;
  if (engineTarget) input.targetDepth = view->depth;
  return renderer.prepare(input);
}

SmokeRenderer::SmokeRenderer(Device& device, SmokeSimulation& simulation, const RendererOptions& options)
    : impl_(std::make_unique<Impl>(runtime::Access::context(device), runtime::Access::pipelineCache(device),
                                   simulation, options, nullptr)) {}

SmokeRenderer::SmokeRenderer(Device& device, SmokeSimulation& simulation, const RendererOptions& options,
                             const RenderTarget& target)
    : impl_(std::make_unique<Impl>(runtime::Access::context(device), runtime::Access::pipelineCache(device),
                                   simulation, options, &target)) {}

SmokeRenderer::~SmokeRenderer() = default;

void SmokeRenderer::setCamera(const Camera& camera) {
  if (!(camera.near > 0.0f && camera.far > camera.near))
    throw std::invalid_argument("Camera: needs 0 < near < far");
  render::EngineView view;
  view.camera = render::Camera::lookAt(camera.position, camera.target, camera.up, camera.fovYDegrees);
  view.plane = render::fullFrame(view.camera, int(width()), int(height()));
  view.depth = render::depthMapping({camera.near, camera.far});
  impl_->view = view;
}

void SmokeRenderer::setViewProjection(const glm::mat4& view, const glm::mat4& projection) {
  impl_->view = render::engineView(view, projection);
}

void SmokeRenderer::setLights(const std::vector<Light>& lights) {
  if (lights.size() > maxLights())
    throw std::invalid_argument("SmokeRenderer::setLights: " + std::to_string(lights.size()) +
                                " lights; at most " + std::to_string(maxLights()));
  std::vector<scene::Light> converted;
  for (const Light& l : lights) converted.push_back(runtime::sceneLight(l));
  impl_->lights = std::move(converted);
}

void SmokeRenderer::render() {
  if (impl_->engineTarget) throw std::invalid_argument("SmokeRenderer::render: an engine target is recorded");
  impl_->last = &impl_->prepare();
  impl_->last->submit();
}

void SmokeRenderer::record(VkCommandBuffer commands, uint64_t frame) {
  if (!impl_->engineTarget) throw std::invalid_argument("SmokeRenderer::record: needs an engine target");
  if (!impl_->view)
    throw std::invalid_argument("SmokeRenderer::record: set the engine's camera first (setViewProjection)");
  impl_->last = &impl_->prepare();
  impl_->last->record(commands, frame);
}

std::vector<StageTime> SmokeRenderer::stageTimes() const {
  std::vector<StageTime> times;
  if (impl_->last)
    for (const gpu::StageTime& t : impl_->last->stageTimes()) times.push_back({t.name, t.milliseconds});
  return times;
}

std::vector<std::string> SmokeRenderer::notes() const {
  return impl_->renderer.notes();
}

std::vector<float> SmokeRenderer::image() const {
  if (impl_->engineTarget) throw std::invalid_argument("SmokeRenderer::image: the engine owns the target");
  const std::vector<uint16_t> halves = impl_->renderer.frame().color().download<uint16_t>();
  std::vector<float> pixels(halves.size());
  for (size_t i = 0; i < halves.size(); ++i) pixels[i] = glm::unpackHalf1x16(halves[i]);
  return pixels;
}

uint32_t SmokeRenderer::maxLights() const {
  return impl_->renderer.frame().maxLights();
}

uint32_t SmokeRenderer::width() const {
  return impl_->renderer.frame().width();
}

uint32_t SmokeRenderer::height() const {
  return impl_->renderer.frame().height();
}

LightmapTextures SmokeRenderer::lightmaps() const {
  const runtime::RealtimeFrame& frame = impl_->renderer.frame();
  const gpu::Image& a = frame.lightmaps().a;
  return {a.handle(),      frame.lightmaps().b.handle(),
          a.view(),        frame.lightmaps().b.view(),
          a.desc().format, a.desc().width,
          a.desc().height, frame.billboardCorners()};
}

}  // namespace sixway
