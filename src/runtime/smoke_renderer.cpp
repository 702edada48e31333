#include <sixway/smoke_renderer.h>

#include <algorithm>
#include <filesystem>
#include <glm/gtc/packing.hpp>

#include "io/error.h"
#include "io/safetensors.h"
#include "nn/network.h"
#include "render/billboard.h"
#include "render/camera.h"
#include "render/guiding_map.h"
#include "render/lightmap_images.h"
#include "render/obstacle_meshes.h"
#include "render/obstacle_pass.h"
#include "render/projection.h"
#include "render/recorded_sequence.h"
#include "render/scene_frame.h"
#include "render/shadow_maps.h"
#include "render/sixway_shading.h"
#include "runtime/smoke_simulation_impl.h"

namespace sixway {
namespace {

constexpr VkFormat kOwnColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

gpu::Image ownImage(const gpu::Context& context, uint32_t width, uint32_t height, VkFormat format,
                    VkImageUsageFlags usage, const char* name) {
  return gpu::Image(context, {width, height, 1, format, usage, name});
}

std::unique_ptr<nn::Network> loadNetwork(const gpu::Context& context, const gpu::PipelineCache& cache,
                                         const RendererOptions& options, uint32_t size) {
  if (!std::filesystem::is_regular_file(options.weights))
    throw io::InputError(options.weights.string(), "no such weights file");
  nn::NetworkOptions networkOptions;
  networkOptions.precision = options.fp16 ? nn::Precision::Fp16 : nn::Precision::Fp32;
  return std::make_unique<nn::Network>(context, cache, io::readSafetensors(options.weights), size, size,
                                       networkOptions);
}

}  // namespace

// The passes of the real-time frame (docs/real-time-rendering.md), recorded once per volume and replayed.
struct SmokeRenderer::Impl {
  Impl(Device::Impl& device, SmokeSimulation::Impl& simulation, const RendererOptions& options,
       const RenderTarget* target)
      : context(*device.context),
        simulation(simulation),
        scene(simulation.scene),
        engineTarget(target != nullptr),
        width(target ? target->width : uint32_t(scene.render.width)),
        height(target ? target->height : uint32_t(scene.render.height)),
        lightmapSize(uint32_t(scene.render.lightmapSize)),
        color(target ? gpu::Image::borrowed(context, target->colorImage, target->colorView,
                                            {width, height, 1, target->colorFormat,
                                             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "engine colour"})
                     : ownImage(context, width, height, kOwnColorFormat,
                                VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "frame colour")),
        depth(target ? gpu::Image::borrowed(context, target->depthImage, target->depthView,
                                            {width, height, 1, target->depthFormat, VK_IMAGE_USAGE_SAMPLED_BIT,
                                             "engine depth"})
                     : ownImage(context, width, height, VK_FORMAT_D32_SFLOAT,
                                VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                "frame depth")),
        guide(ownImage(context, lightmapSize, lightmapSize, kOwnColorFormat,
                       VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "guiding map")),
        lightmaps(context, lightmapSize, lightmapSize),
        meshes(context, scene.obstacles),
        shadowMaps(context, *device.cache, render::kDefaultShadowTileSize,
                   options.shadows ? render::shadowTileCount(scene.lights, scene.obstacles) : 0),
        guiding(context, *device.cache, render::GuideSettings::fromScene(scene)),
        shading(context, *device.cache, color.desc().format),
        network(loadNetwork(context, *device.cache, options, lightmapSize)),
        sequence(context) {
    if (target && (!target->colorImage || !target->colorView || !target->depthImage || !target->depthView ||
                   target->width == 0 || target->height == 0))
      throw std::invalid_argument("RenderTarget: colour and depth images, views and a size are needed");
    // The engine draws its own scene; on sixway's own image the scene's obstacles are drawn first.
    if (!engineTarget) obstacles = std::make_unique<render::ObstaclePass>(context, *device.cache, scene.render.background);
    controls.emissiveGradient = render::emissiveGradientFromRamp(scene.smoke.emission);
  }

  // Records the frame's passes for the simulation's volume (once) and writes this frame's values.
  gpu::Sequence& prepare() {
    const render::Volume volume = simulation.volumes.currentVolume();
    gpu::Sequence& s = sequence.get({render::handleKey(volume.density->handle())}, [&](gpu::Sequence& s) {
      shadowMaps.record(s, meshes);
      if (obstacles) obstacles->record(s, meshes, shadowMaps, color, depth);
      guiding.record(s, volume, guide);
      s.beginStage("network");
      network->record(s, guide, lightmaps.a, lightmaps.b);
      s.endStage();
      shading.record(s, lightmaps.a, lightmaps.b, &guide, &depth,
                     render::ShadowAtlas{&shadowMaps.atlas(), shadowMaps.tileSize()}, color);
    });
    const sim::Simulation& sim = simulation.volumes.simulation();
    for (size_t o = 0; o < scene.obstacles.size(); ++o) meshes.setMotion(o, sim.obstacleMotion(o));
    meshes.update(sim.seconds());

    const int index = std::max(0, simulation.frames - 1);  // the smoke after `frames` frames is frame frames − 1
    const render::Camera view =
        camera ? render::Camera::lookAt(camera->position, camera->target, camera->up, camera->fovYDegrees)
               : render::sceneCamera(scene.camera, index);
    const std::vector<io::Light> lights = render::sceneLights(scene.lights, index);
    const render::Box bounds = render::sceneBounds(render::domainBox(scene.grid), meshes);
    const render::ImagePlane frame = render::fullFrame(view, int(width), int(height));
    // The depth buffer's range: the engine's projection, or the one the obstacle pass draws with.
    const render::DepthRange sceneRange = engineTarget ? render::DepthRange{camera->near, camera->far}
                                                       : render::boxDepthRange(view, bounds);
    shadowMaps.update(lights, bounds, meshes);
    if (obstacles) obstacles->update(view, frame, sceneRange, lights, scene.ambient, shadowMaps);
    const render::Box volumeBox = volume.grid.bounds();
    const render::ImagePlane billboard = render::billboardBounds(view, volumeBox, 1.0f);
    const render::DepthRange shellRange = render::boxDepthRange(view, volumeBox);
    guiding.update(view, billboard, shellRange, scene.smoke, uint32_t(index));
    std::vector<render::ShadingLight> shadingLights;
    for (size_t l = 0; l < lights.size(); ++l)
      shadingLights.push_back(
          render::shadingLight(lights[l], shadowMaps.tileOf(l), shadowMaps.lightViewProjection(l)));
    shading.update(view, frame, billboard, shellRange, sceneRange, shadingLights, scene.ambient, controls);
    return s;
  }

  const gpu::Context& context;
  SmokeSimulation::Impl& simulation;
  const io::Scene& scene;
  bool engineTarget;
  uint32_t width, height, lightmapSize;
  gpu::Image color, depth, guide;
  render::LightmapImages lightmaps;
  render::ObstacleMeshes meshes;
  render::ShadowMaps shadowMaps;
  std::unique_ptr<render::ObstaclePass> obstacles;
  render::GuidingMap guiding;
  render::SixWayShading shading;
  std::unique_ptr<nn::Network> network;
  render::ShadingControls controls;
  render::RecordedSequence sequence;
  std::optional<Camera> camera;
  gpu::Sequence* last = nullptr;
};

SmokeRenderer::SmokeRenderer(Device& device, SmokeSimulation& simulation, const RendererOptions& options)
    : impl_(std::make_unique<Impl>(device.impl(), simulation.impl(), options, nullptr)) {}

SmokeRenderer::SmokeRenderer(Device& device, SmokeSimulation& simulation, const RendererOptions& options,
                             const RenderTarget& target)
    : impl_(std::make_unique<Impl>(device.impl(), simulation.impl(), options, &target)) {}

SmokeRenderer::~SmokeRenderer() = default;

void SmokeRenderer::setCamera(const Camera& camera) {
  if (!(camera.near > 0.0f && camera.far > camera.near))
    throw std::invalid_argument("Camera: needs 0 < near < far");
  render::Camera::lookAt(camera.position, camera.target, camera.up, camera.fovYDegrees);  // checks the axes
  impl_->camera = camera;
}

void SmokeRenderer::render() {
  if (impl_->engineTarget) throw std::invalid_argument("SmokeRenderer::render: an engine target is recorded");
  impl_->last = &impl_->prepare();
  impl_->last->submit();
}

void SmokeRenderer::record(VkCommandBuffer commands, uint64_t frame) {
  if (!impl_->engineTarget) throw std::invalid_argument("SmokeRenderer::record: needs an engine target");
  if (!impl_->camera) throw std::invalid_argument("SmokeRenderer::record: set the engine's camera first");
  impl_->last = &impl_->prepare();
  impl_->last->record(commands, frame);
}

std::vector<StageTime> SmokeRenderer::stageTimes() const {
  std::vector<StageTime> times;
  if (impl_->last)
    for (const gpu::StageTime& t : impl_->last->stageTimes()) times.push_back({t.name, t.milliseconds});
  return times;
}

std::vector<float> SmokeRenderer::image() const {
  if (impl_->engineTarget) throw std::invalid_argument("SmokeRenderer::image: the engine owns the target");
  const std::vector<uint16_t> halves = impl_->color.download<uint16_t>();
  std::vector<float> pixels(halves.size());
  for (size_t i = 0; i < halves.size(); ++i) pixels[i] = glm::unpackHalf1x16(halves[i]);
  return pixels;
}

uint32_t SmokeRenderer::width() const {
  return impl_->width;
}

uint32_t SmokeRenderer::height() const {
  return impl_->height;
}

VkImage SmokeRenderer::lightmapA() const {
  return impl_->lightmaps.a.handle();
}

VkImage SmokeRenderer::lightmapB() const {
  return impl_->lightmaps.b.handle();
}

}  // namespace sixway
