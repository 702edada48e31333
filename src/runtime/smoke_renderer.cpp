#include <sixway/smoke_renderer.h>

#include <algorithm>
#include <glm/gtc/packing.hpp>
#include <stdexcept>

#include "gpu/image.h"
#include "render/scene_frame.h"
#include "render/shadow_maps.h"
#include "runtime/internal.h"
#include "runtime/network_lightmaps.h"
#include "runtime/network_weights.h"
#include "runtime/placement.h"
#include "runtime/scene_lights.h"
#include "runtime/smoke_renderer_impl.h"

namespace sixway {
namespace {

// The fixed target of the RenderTarget constructor as every frame's targets, in VK_IMAGE_LAYOUT_GENERAL.
FrameTargets fixedTargets(const RenderTarget& target) {
  if (!target.colorImage || !target.colorView || !target.depthImage || !target.depthView ||
      target.width == 0 || target.height == 0)
    throw std::invalid_argument("RenderTarget: colour and depth images, views and a size are needed");
  if (!gpu::isDepthFormat(target.depthFormat))
    throw std::invalid_argument("RenderTarget: depth format " + std::to_string(target.depthFormat) +
                                " is not D16, D24 or D32 (with or without stencil)");
  FrameTargets targets;
  targets.color = {target.colorImage, target.colorView, target.colorFormat};
  targets.depth = {target.depthImage, target.depthView, target.depthFormat};
  targets.width = target.width;
  targets.height = target.height;
  return targets;
}

void requireLayouts(const TargetImage& image, const char* which) {
  for (VkImageLayout layout : {image.layout, image.finalLayout})
    if (layout == VK_IMAGE_LAYOUT_UNDEFINED || layout == VK_IMAGE_LAYOUT_PREINITIALIZED)
      throw std::invalid_argument(std::string("FrameTargets: the ") + which +
                                  " image's layouts may not be UNDEFINED or PREINITIALIZED (its contents are "
                                  "read)");
}

// A depth-only layout says nothing of a stencil aspect, which the layout change moves too.
void requireStencilLayouts(const TargetImage& depth) {
  if (!gpu::hasStencil(depth.format)) return;
  for (VkImageLayout layout : {depth.layout, depth.finalLayout})
    if (layout == VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL ||
        layout == VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL)
      throw std::invalid_argument(
          "FrameTargets: a depth image with stencil needs a layout of both aspects (e.g. "
          "DEPTH_STENCIL_ATTACHMENT_OPTIMAL), not a depth-only one");
}

runtime::EngineTarget borrowedTarget(const gpu::Context& context, const FrameTargets& t) {
  if (!t.color.image || !t.color.view || !t.depth.image || !t.depth.view || t.width == 0 || t.height == 0)
    throw std::invalid_argument("FrameTargets: colour and depth images, views and a size are needed");
  requireLayouts(t.color, "colour");
  requireLayouts(t.depth, "depth");
  requireStencilLayouts(t.depth);
  return {gpu::Image::borrowed(
              context, t.color.image, t.color.view,
              {t.width, t.height, 1, t.color.format, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "engine colour"}),
          gpu::Image::borrowed(
              context, t.depth.image, t.depth.view,
              {t.width, t.height, 1, t.depth.format, VK_IMAGE_USAGE_SAMPLED_BIT, "engine depth"}),
          t.viewport};
}

void changeLayouts(VkCommandBuffer commands, const FrameTargets& t, bool toGeneral) {
  for (const TargetImage* image : {&t.color, &t.depth}) {
    const VkImageLayout engine = toGeneral ? image->layout : image->finalLayout;
    if (engine == VK_IMAGE_LAYOUT_GENERAL) continue;
    gpu::recordLayoutChange(commands, image->image, image->format,
                            toGeneral ? engine : VK_IMAGE_LAYOUT_GENERAL,
                            toGeneral ? VK_IMAGE_LAYOUT_GENERAL : engine);
  }
}

uint32_t shadowTiles(const scene::Scene& scene, const RendererOptions& options) {
  if (!options.shadows) return 0;
  return options.shadowedLights ? *options.shadowedLights
                                : render::shadowTileCount(scene.lights, scene.obstacles);
}

io::SafetensorsFile weightsOf(const RendererOptions& options) {
  if (options.weightsData.empty()) return runtime::readWeights(options.weights);
  return runtime::readWeights(options.weightsData, options.weights);
}

}  // namespace

SmokeRenderer::Impl::Impl(const gpu::Context& context, const gpu::PipelineCache& cache,
                          const SmokeSimulation& simulation, const RendererOptions& options,
                          std::optional<runtime::FrameTarget> engine)
    : context(context),
      simulation(simulation),
      scene(runtime::Access::scene(simulation)),
      engineTarget(engine.has_value()),
      insideRendering(engine && std::holds_alternative<render::ShadingTargetFormats>(*engine)),
      renderer(
          context, cache, scene,
          engine.value_or(runtime::OwnTarget{uint32_t(scene.render.width), uint32_t(scene.render.height)}),
          shadowTiles(scene, options), networkSource(context, cache, scene, options)),
      obstaclesOf{runtime::Access::starts(simulation), 0} {
  static const char* const kPresets[] = {"unity", "rlt-bbf", "o3de"};
  network().packLightmaps(context, cache, render::packingPreset(kPresets[int(options.packing)]));
}

std::unique_ptr<runtime::NetworkLightmaps> SmokeRenderer::Impl::networkSource(
    const gpu::Context& context, const gpu::PipelineCache& cache, const scene::Scene& scene,
    const RendererOptions& options) {
  if (!options.shareNetwork)
    return std::make_unique<runtime::NetworkLightmaps>(context, cache, scene, weightsOf(options),
                                                       options.fp16);
  const auto& other = options.shareNetwork->impl_->network();
  if (&options.shareNetwork->impl_->context != &context)
    throw std::invalid_argument("RendererOptions::shareNetwork: a renderer of another device");
  try {
    return std::make_unique<runtime::NetworkLightmaps>(scene, other);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("RendererOptions::shareNetwork: ") + e.what());
  }
}

std::optional<render::EngineView> SmokeRenderer::Impl::sceneView() const {
  const glm::mat4 placement = simulation.placement();
  if (const Camera* c = std::get_if<Camera>(&camera)) {
    render::EngineView view;
    view.camera = render::Camera::lookAt(runtime::scenePoint(placement, c->position),
                                         runtime::scenePoint(placement, c->target),
                                         runtime::sceneDirection(placement, c->up), c->fovYDegrees);
    view.depth = render::depthMapping({c->near, c->far});
    return view;
  }
  if (const Matrices* m = std::get_if<Matrices>(&camera))
    return render::engineView(m->view * placement, m->projection);
  return std::nullopt;
}

std::optional<std::vector<scene::Light>> SmokeRenderer::Impl::sceneLights() const {
  if (!lights) return std::nullopt;
  const glm::mat4 placement = simulation.placement();
  std::vector<scene::Light> converted;
  for (Light l : *lights) {
    l.direction = runtime::sceneDirection(placement, l.direction);
    l.position = runtime::scenePoint(placement, l.position);
    converted.push_back(runtime::sceneLight(l));
  }
  return converted;
}

gpu::Sequence& SmokeRenderer::Impl::prepare(std::optional<uint64_t> frame) {
  const runtime::SimulatedVolumes& volumes = runtime::Access::volumes(simulation);
  const sim::Simulation& sim = volumes.simulation();
  // The engine's obstacles (SmokeSimulation::setObstacles), or the scene's again after a restart.
  const std::pair<uint64_t, uint64_t> obstacles{runtime::Access::starts(simulation), sim.obstacleSetsMade()};
  if (obstacles != obstaclesOf) {
    renderer.replaceObstacles(sim.scene().obstacles, frame);
    obstaclesOf = obstacles;
  }
  for (size_t o = 0; o < sim.scene().obstacles.size(); ++o)
    renderer.frame().meshes().setMotion(o, sim.obstacleMotion(o));
  // The smoke after `frames` frames is frame frames − 1.
  const int index = std::max(0, simulation.framesSimulated() - 1);
  const std::optional<render::EngineView> view = sceneView();
  const std::optional<std::vector<scene::Light>> frameLights = sceneLights();
  runtime::FrameInput input{volumes.currentVolume(),
                            runtime::Access::starts(simulation),
                            {view ? view->camera : render::sceneCamera(scene.camera, index),
                             frameLights ? *frameLights : render::sceneLights(scene.lights, index)},
                            index,
                            sim.seconds()};
  // A restarted simulation may reuse a handle value: the start count tells its volume apart. An engine's
  // depth buffer holds its projection's depth; sixway's own, the obstacle pass's. setCamera's image plane is
  // the target's (or viewport's) full frame.
  if (std::holds_alternative<Matrices>(camera)) input.plane = view->plane;
  if (engineTarget) input.targetDepth = view->depth;
  input.frame = frame;
  return renderer.prepare(input);
}

void SmokeRenderer::Impl::record(VkCommandBuffer commands, uint64_t frame, const FrameTargets& targets) {
  if (std::holds_alternative<std::monostate>(camera))
    throw std::invalid_argument("SmokeRenderer::record: set the engine's camera first (setViewProjection)");
  last = lastComposite = nullptr;  // until both are recorded: either may be replaced on the way
  renderer.frame().setEngineTarget(borrowedTarget(context, targets));
  gpu::Sequence& compute = prepare(frame);
  gpu::Sequence& composite = renderer.composite();
  compute.record(commands, frame);
  changeLayouts(commands, targets, true);
  composite.record(commands, frame);
  changeLayouts(commands, targets, false);
  last = &compute;
  lastComposite = &composite;
}

SmokeRenderer::SmokeRenderer(Device& device, SmokeSimulation& simulation, const RendererOptions& options)
    : impl_(std::make_unique<Impl>(runtime::Access::context(device), runtime::Access::pipelineCache(device),
                                   simulation, options, std::nullopt)) {}

SmokeRenderer::SmokeRenderer(Device& device, SmokeSimulation& simulation, const RendererOptions& options,
                             const RenderTarget& target)
    : SmokeRenderer(device, simulation, options, target.colorFormat) {
  impl_->fixedTargets = fixedTargets(target);
  impl_->renderer.frame().setEngineTarget(borrowedTarget(impl_->context, *impl_->fixedTargets));
}

SmokeRenderer::SmokeRenderer(Device& device, SmokeSimulation& simulation, const RendererOptions& options,
                             VkFormat colorFormat)
    : impl_(std::make_unique<Impl>(runtime::Access::context(device), runtime::Access::pipelineCache(device),
                                   simulation, options, runtime::FrameTarget(colorFormat))) {}

SmokeRenderer::SmokeRenderer(Device& device, SmokeSimulation& simulation, const RendererOptions& options,
                             const RenderingFormats& rendering)
    : impl_(std::make_unique<Impl>(runtime::Access::context(device), runtime::Access::pipelineCache(device),
                                   simulation, options,
                                   runtime::FrameTarget(render::ShadingTargetFormats{
                                       rendering.colors, rendering.depth, rendering.stencil}))) {}

SmokeRenderer::~SmokeRenderer() = default;

void SmokeRenderer::setCamera(const Camera& camera) {
  if (!(camera.near > 0.0f && camera.far > camera.near))
    throw std::invalid_argument("Camera: needs 0 < near < far");
  render::Camera::lookAt(camera.position, camera.target, camera.up, camera.fovYDegrees);  // checks it
  impl_->camera = camera;
}

void SmokeRenderer::setViewProjection(const glm::mat4& view, const glm::mat4& projection) {
  render::engineView(view, projection);  // checks them
  impl_->camera = Impl::Matrices{view, projection};
}

void SmokeRenderer::setLights(const std::vector<Light>& lights) {
  if (lights.size() > maxLights())
    throw std::invalid_argument("SmokeRenderer::setLights: " + std::to_string(lights.size()) +
                                " lights; at most " + std::to_string(maxLights()));
  for (const Light& l : lights) runtime::sceneLight(l);  // checks each
  impl_->lights = lights;
}

void SmokeRenderer::render() {
  if (impl_->engineTarget) throw std::invalid_argument("SmokeRenderer::render: an engine target is recorded");
  impl_->last = &impl_->prepare(std::nullopt);
  impl_->last->submit();
}

void SmokeRenderer::record(VkCommandBuffer commands, uint64_t frame) {
  if (impl_->insideRendering)
    throw std::invalid_argument(
        "SmokeRenderer::record: drawn inside the engine's rendering: recordLightmaps and recordComposite");
  if (!impl_->fixedTargets)
    throw std::invalid_argument(impl_->engineTarget
                                    ? "SmokeRenderer::record: pass this frame's targets (FrameTargets)"
                                    : "SmokeRenderer::record: needs an engine target");
  impl_->record(commands, frame, *impl_->fixedTargets);
}

void SmokeRenderer::record(VkCommandBuffer commands, uint64_t frame, const FrameTargets& targets) {
  if (!impl_->engineTarget || impl_->insideRendering)
    throw std::invalid_argument(
        impl_->insideRendering
            ? "SmokeRenderer::record: drawn inside the engine's rendering: recordLightmaps "
              "and recordComposite"
            : "SmokeRenderer::record: needs an engine target");
  impl_->record(commands, frame, targets);
}

void SmokeRenderer::recordLightmaps(VkCommandBuffer commands, uint64_t frame,
                                    const CompositeTargets& targets) {
  if (!impl_->insideRendering)
    throw std::invalid_argument(
        "SmokeRenderer::recordLightmaps: the renderer was not made for the engine's rendering "
        "(RenderingFormats)");
  if (std::holds_alternative<std::monostate>(impl_->camera))
    throw std::invalid_argument(
        "SmokeRenderer::recordLightmaps: set the engine's camera first (setViewProjection)");
  if (!targets.depth || !targets.depthView || targets.width == 0 || targets.height == 0)
    throw std::invalid_argument("CompositeTargets: a depth image, its view and a size are needed");
  const gpu::ImageDesc depth{
      targets.width, targets.height, 1, targets.depthFormat, VK_IMAGE_USAGE_SAMPLED_BIT, "engine depth"};
  impl_->last = impl_->lastComposite = nullptr;
  impl_->renderer.frame().setInsideTarget(
      {gpu::Image::borrowed(impl_->context, targets.depth, targets.depthView, depth),
       targets.depthLayout,
       {targets.width, targets.height},
       targets.viewport});
  gpu::Sequence& compute = impl_->prepare(frame);
  compute.record(commands, frame);
  impl_->renderer.frame().recordShadingParameters(commands);
  if (!impl_->compositeTimes) impl_->compositeTimes.emplace(impl_->context);
  impl_->compositeTimes->recordReset(commands, frame);
  impl_->last = &compute;
}

void SmokeRenderer::recordComposite(VkCommandBuffer commands) const {
  if (!impl_->insideRendering || !impl_->last)
    throw std::invalid_argument(
        "SmokeRenderer::recordComposite: after recordLightmaps of the frame, on a renderer "
        "made for the engine's rendering");
  impl_->compositeTimes->recordBegin(commands);
  impl_->renderer.frame().recordCompositeInside(commands);
  impl_->compositeTimes->recordEnd(commands);
}

void SmokeRenderer::forgetTargets() {
  impl_->renderer.forgetComposites();
}

std::vector<StageTime> SmokeRenderer::stageTimes() const {
  std::vector<StageTime> times;
  for (const gpu::Sequence* s : {impl_->last, impl_->lastComposite})
    if (s)
      for (const gpu::StageTime& t : s->stageTimes()) times.push_back({t.name, t.milliseconds});
  if (impl_->compositeTimes && impl_->compositeTimes->milliseconds())
    times.push_back({"shade", *impl_->compositeTimes->milliseconds()});
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
  const render::LightmapRepack* packed = impl_->network().packed();
  const gpu::Image& a = packed ? packed->texture(0) : frame.lightmaps().a;
  const gpu::Image& b = packed ? packed->texture(1) : frame.lightmaps().b;
  std::array<glm::vec3, 4> corners = frame.billboardCorners();
  for (glm::vec3& c : corners) c = runtime::worldPoint(impl_->simulation.placement(), c);
  return {a.handle(),      b.handle(),     a.view(),        b.view(),
          a.desc().format, a.desc().width, a.desc().height, corners};
}

}  // namespace sixway
