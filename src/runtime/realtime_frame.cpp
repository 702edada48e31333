#include "runtime/realtime_frame.h"

#include "render/billboard.h"
#include "render/scene_frame.h"

namespace sixway::runtime {
namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

gpu::Image ownImage(const gpu::Context& context, uint32_t width, uint32_t height, VkFormat format,
                    VkImageUsageFlags usage, const char* name) {
  return gpu::Image(context, {width, height, 1, format, usage, name});
}

}  // namespace

RealtimeFrame::RealtimeFrame(const gpu::Context& context, const gpu::PipelineCache& cache,
                             const scene::Scene& scene, FrameTarget target, uint32_t shadowTiles,
                             const render::GuideSettings& guide)
    : scene_(&scene),
      width_(target.width),
      height_(target.height),
      lightmapSize_(uint32_t(scene.render.lightmapSize)),
      engineColor_(std::move(target.engineColor)),
      engineDepth_(std::move(target.engineDepth)),
      guide_(ownImage(context, lightmapSize_, lightmapSize_, kColorFormat,
                      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "guiding map")),
      lightmaps_(context, lightmapSize_, lightmapSize_),
      meshes_(context, scene.obstacles),
      shadowMaps_(context, cache, render::kDefaultShadowTileSize, shadowTiles),
      guiding_(context, cache, guide),
      shading_(context, cache, engineColor_ ? engineColor_->desc().format : kColorFormat) {
  if (engineColor_.has_value() != engineDepth_.has_value())
    throw std::invalid_argument("RealtimeFrame: an engine target needs both colour and depth");
  if (!engineColor_) {
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

void RealtimeFrame::record(gpu::Sequence& s, const render::Volume& volume, FrameStages stages,
                           const std::function<void(gpu::Sequence&)>& lightmapStage) {
  shadowMaps_.record(s, meshes_);
  if (obstacles_) obstacles_->record(s, meshes_, shadowMaps_, color(), depth(), &volume, scene_->smoke);
  if (stages == FrameStages::ObstaclesOnly) return;
  if (stages != FrameStages::AllButGuide) guiding_.record(s, volume, guide_, guideEmission());
  if (stages == FrameStages::UpToGuide) return;
  if (lightmapStage) lightmapStage(s);
  shading_.record(s, lightmaps_.a, lightmaps_.b, &guide_, &guiding_.opacityDepths(), &depth(),
                  render::ShadowAtlas{&shadowMaps_.atlas(), shadowMaps_.tileSize()}, color());
}

void RealtimeFrame::updateScene(const render::Camera& camera, const std::vector<scene::Light>& lights,
                                double seconds, const std::optional<render::ImagePlane>& plane,
                                std::optional<render::DepthMapping> targetDepth) {
  meshes_.update(seconds);
  const render::Box bounds = render::sceneBounds(render::domainBox(scene_->grid), meshes_);
  frame_ = plane.value_or(render::fullFrame(camera, int(width_), int(height_)));
  const render::DepthRange obstacleRange = render::boxDepthRange(camera, bounds);
  targetDepth_ = targetDepth.value_or(render::depthMapping(obstacleRange));
  shadowMaps_.update(lights, bounds, meshes_);
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
