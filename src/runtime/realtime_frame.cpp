#include "runtime/realtime_frame.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "gpu/one_shot.h"
#include "render/billboard.h"
#include "render/recorded_sequence.h"
#include "render/scene_frame.h"

namespace sixway::runtime {
namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

gpu::Image ownImage(const gpu::Context& context, uint32_t width, uint32_t height, VkFormat format,
                    VkImageUsageFlags usage, const char* name) {
  return gpu::Image(context, {width, height, 1, format, usage, name});
}

render::ShadingTargetFormats shadingFormats(const FrameTarget& target) {
  if (const auto* formats = std::get_if<render::ShadingTargetFormats>(&target)) return *formats;
  if (const auto* format = std::get_if<VkFormat>(&target)) return {{*format}};
  return {{kColorFormat}};
}

// A rectangle inside `size` ({0, 0, 0, 0}: all of it); std::invalid_argument otherwise.
VkRect2D viewportIn(VkRect2D v, VkExtent2D size) {
  if (v.offset.x == 0 && v.offset.y == 0 && v.extent.width == 0 && v.extent.height == 0)
    return {{0, 0}, size};
  if (v.offset.x < 0 || v.offset.y < 0 || v.extent.width == 0 || v.extent.height == 0 ||
      uint64_t(v.offset.x) + v.extent.width > size.width ||
      uint64_t(v.offset.y) + v.extent.height > size.height)
    throw std::invalid_argument("the viewport (" + std::to_string(v.offset.x) + ", " +
                                std::to_string(v.offset.y) + ") " + std::to_string(v.extent.width) + "x" +
                                std::to_string(v.extent.height) + " is not a rectangle inside the " +
                                std::to_string(size.width) + "x" + std::to_string(size.height) + " target");
  return v;
}

bool sampledDepthLayout(VkImageLayout layout) {
  switch (layout) {
    case VK_IMAGE_LAYOUT_GENERAL:
    case VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL:
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL:
    case VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_STENCIL_ATTACHMENT_OPTIMAL:
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL:
    case VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL:
      return true;
    default:
      return false;
  }
}

}  // namespace

RealtimeFrame::RealtimeFrame(const gpu::Context& context, const gpu::PipelineCache& cache,
                             const scene::Scene& scene, FrameTarget target, uint32_t shadowTiles,
                             const render::GuideSettings& guide)
    : scene_(&scene),
      lightmapSize_(uint32_t(scene.render.lightmapSize)),
      engineFormat_(std::holds_alternative<VkFormat>(target) ? std::optional(std::get<VkFormat>(target))
                                                             : std::nullopt),
      insideRendering_(std::holds_alternative<render::ShadingTargetFormats>(target)),
      guide_(ownImage(context, lightmapSize_, lightmapSize_, kColorFormat,
                      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "guiding map")),
      lightmaps_(context, lightmapSize_, lightmapSize_),
      meshes_(std::make_unique<render::ObstacleMeshes>(context, scene.obstacles)),
      shadowMaps_(context, cache, render::kDefaultShadowTileSize, shadowTiles),
      guiding_(context, cache, guide),
      shading_(context, cache, shadingFormats(target)) {
  if (const OwnTarget* own = std::get_if<OwnTarget>(&target)) {
    width_ = own->width;
    height_ = own->height;
    color_ = ownImage(context, width_, height_, kColorFormat,
                      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "frame colour");
    depth_ =
        ownImage(context, width_, height_, VK_FORMAT_D32_SFLOAT,
                 VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "frame depth");
    obstacles_ = std::make_unique<render::ObstaclePass>(context, cache, scene.render.background);
  }
  if (guide.emission) guideEmission_.emplace(context, guiding_.emissionDesc());
  controls_.emissiveGradient = render::emissiveGradientFromRamp(scene.smoke.emission);
  controls_.emissiveStraightScale = render::emissiveStraightScale(scene.smoke);
}

std::unique_ptr<render::ObstacleMeshes> RealtimeFrame::replaceObstacles(
    std::unique_ptr<render::ObstacleMeshes> meshes) {
  return std::exchange(meshes_, std::move(meshes));
}

void RealtimeFrame::setEngineTarget(EngineTarget target) {
  if (!engineFormat_) throw std::invalid_argument("RealtimeFrame: drawn into its own target");
  const gpu::ImageDesc& color = target.color.desc();
  const gpu::ImageDesc& depth = target.depth.desc();
  if (color.format != *engineFormat_)
    throw std::invalid_argument("the colour target's format " + std::to_string(color.format) +
                                " is not the format the renderer was made for, " +
                                std::to_string(*engineFormat_));
  if (!gpu::isDepthFormat(depth.format))
    throw std::invalid_argument("the depth target's format " + std::to_string(depth.format) +
                                " is not D16, D24 or D32 (with or without stencil)");
  if (depth.width != color.width || depth.height != color.height)
    throw std::invalid_argument("the depth target is " + std::to_string(depth.width) + "x" +
                                std::to_string(depth.height) + ", the colour target " +
                                std::to_string(color.width) + "x" + std::to_string(color.height));
  target.viewport = viewportIn(target.viewport, {color.width, color.height});
  width_ = target.viewport.extent.width;
  height_ = target.viewport.extent.height;
  engine_ = std::move(target);
}

void RealtimeFrame::setInsideTarget(InsideTarget target) {
  if (!insideRendering_) throw std::invalid_argument("RealtimeFrame: not drawn inside an engine's rendering");
  const gpu::ImageDesc& depth = target.depth.desc();
  if (!gpu::isDepthFormat(depth.format))
    throw std::invalid_argument("the depth image's format " + std::to_string(depth.format) +
                                " is not D16, D24 or D32 (with or without stencil)");
  if (depth.width != target.size.width || depth.height != target.size.height)
    throw std::invalid_argument("the depth image is " + std::to_string(depth.width) + "x" +
                                std::to_string(depth.height) + ", the rendering " +
                                std::to_string(target.size.width) + "x" + std::to_string(target.size.height));
  if (!sampledDepthLayout(target.depthLayout))
    throw std::invalid_argument(
        "the depth image's layout " + std::to_string(target.depthLayout) +
        " cannot be sampled inside the rendering: a read-only depth layout or GENERAL");
  target.viewport = viewportIn(target.viewport, target.size);
  width_ = target.viewport.extent.width;
  height_ = target.viewport.extent.height;
  inside_ = std::move(target);
}

void RealtimeFrame::recordShadingParameters(VkCommandBuffer commands) const {
  shading_.recordParameters(commands);
  gpu::recordFullBarrier(commands);
}

void RealtimeFrame::recordCompositeInside(VkCommandBuffer commands) const {
  if (!inside_) throw std::invalid_argument("RealtimeFrame: no target set for the composite");
  shading_.recordInside(commands, lightmaps_.a, lightmaps_.b, &guide_, &guiding_.opacityDepths(),
                        inside_->depth, inside_->depthLayout,
                        render::ShadowAtlas{&shadowMaps_.atlas(), shadowMaps_.tileSize()}, inside_->size,
                        inside_->viewport);
}

std::vector<uint64_t> RealtimeFrame::engineTargetKey() const {
  if (!engine_) return {};
  const VkRect2D& v = engine_->viewport;
  return {render::handleKey(engine_->color.handle()),
          render::handleKey(engine_->color.view()),
          render::handleKey(engine_->depth.handle()),
          render::handleKey(engine_->depth.view()),
          engine_->color.desc().width,
          engine_->color.desc().height,
          uint64_t(v.offset.x),
          uint64_t(v.offset.y),
          v.extent.width,
          v.extent.height};
}

void RealtimeFrame::record(gpu::Sequence& s, const render::Volume& volume, FrameStages stages,
                           const std::function<void(gpu::Sequence&)>& lightmapStage) {
  shadowMaps_.record(s, *meshes_);
  if (obstacles_) obstacles_->record(s, *meshes_, shadowMaps_, color(), depth(), &volume, scene_->smoke);
  if (stages == FrameStages::ObstaclesOnly) return;
  if (stages != FrameStages::AllButGuide) guiding_.record(s, volume, guide_, guideEmission());
  if (stages == FrameStages::UpToGuide) return;
  if (lightmapStage) lightmapStage(s);
  if (!drawsIntoEngineTarget()) recordShading(s, std::nullopt);
}

void RealtimeFrame::recordComposite(gpu::Sequence& s) {
  if (!engine_) throw std::invalid_argument("RealtimeFrame: no engine target set for the composite");
  recordShading(s, engine_->viewport);
}

void RealtimeFrame::recordShading(gpu::Sequence& s, const std::optional<VkRect2D>& viewport) {
  shading_.record(s, lightmaps_.a, lightmaps_.b, &guide_, &guiding_.opacityDepths(), &depth(),
                  render::ShadowAtlas{&shadowMaps_.atlas(), shadowMaps_.tileSize()}, color(), viewport);
}

void RealtimeFrame::updateScene(const render::Camera& camera, const std::vector<scene::Light>& lights,
                                double seconds, const std::optional<render::ImagePlane>& plane,
                                std::optional<render::DepthMapping> targetDepth) {
  meshes_->update(seconds);
  const render::Box bounds = render::sceneBounds(render::domainBox(scene_->grid), *meshes_);
  frame_ = plane.value_or(render::fullFrame(camera, int(width_), int(height_)));
  const render::DepthRange obstacleRange = render::boxDepthRange(camera, bounds);
  targetDepth_ = targetDepth.value_or(render::depthMapping(obstacleRange));
  shadowMaps_.update(lights, bounds, *meshes_);
  if (obstacles_) obstacles_->update(camera, frame_, obstacleRange, lights, scene_->ambient, shadowMaps_);
}

render::ImagePlane RealtimeFrame::updateGuide(const render::Camera& camera, const render::Box& volumeBox,
                                              int index) {
  const render::ImagePlane billboard = render::billboardBounds(camera, volumeBox, 1.0f);
  guiding_.update(camera, billboard, render::boxDepthRange(camera, volumeBox), scene_->smoke,
                  uint32_t(index));
  return billboard;
}

void RealtimeFrame::updateShading(const render::Camera& camera, const std::vector<scene::Light>& lights,
                                  const render::ImagePlane& billboard, const render::Box& volumeBox) {
  std::vector<render::ShadingLight> shadingLights;
  for (size_t l = 0; l < lights.size(); ++l)
    shadingLights.push_back(
        render::shadingLight(lights[l], shadowMaps_.tileOf(l), shadowMaps_.lightViewProjection(l)));
  const render::DepthRange shell = render::boxDepthRange(camera, volumeBox);
  shading_.update(camera, frame_, billboard, shell, targetDepth_, shadingLights, scene_->ambient, controls_);
  billboardCorners_ = render::billboardCorners(camera, billboard, 0.5f * (shell.near + shell.far));
}

}  // namespace sixway::runtime
