#pragma once
// The passes of the real-time frame (docs/real-time-rendering.md) for one scene, and their per-frame values:
// obstacle shadow maps, the obstacles drawn into the target (sixway's own image only; an engine draws its
// own), the guiding map, a lightmap stage (the network's, or whatever the caller records), and six-way
// shading over the colour target. FrameRenderer (frame_renderer.h) drives them.
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <variant>
#include <vector>

#include "gpu/image.h"
#include "gpu/sequence.h"
#include "render/camera.h"
#include "render/guiding_map.h"
#include "render/lightmap_images.h"
#include "render/obstacle_meshes.h"
#include "render/obstacle_pass.h"
#include "render/projection.h"
#include "render/shadow_maps.h"
#include "render/sixway_shading.h"
#include "render/volume.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Context;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::runtime {

// sixway's own RGBA16F colour + D32 depth of a size, the scene's obstacles drawn first.
struct OwnTarget {
  uint32_t width = 0, height = 0;
};
// An engine's colour and depth images for a frame (borrowed; VK_IMAGE_LAYOUT_GENERAL while the frame's
// composite runs) and the rectangle of them the camera's image covers; the engine draws its scene.
struct EngineTarget {
  gpu::Image color, depth;
  VkRect2D viewport{};
};
// An engine's depth buffer for a composite drawn inside the engine's own rendering (its layout there) and
// the rendering's size and the camera's viewport in it.
struct InsideTarget {
  gpu::Image depth;
  VkImageLayout depthLayout = VK_IMAGE_LAYOUT_GENERAL;
  VkExtent2D size{};
  VkRect2D viewport{};
};
// Where the frame is drawn: its own images; an engine's of this colour format, set per frame
// (RealtimeFrame::setEngineTarget); or inside an engine's rendering of these formats
// (setInsideTarget, recordCompositeInside).
using FrameTarget = std::variant<OwnTarget, VkFormat, render::ShadingTargetFormats>;

// Which passes a recorded frame has: all of them; up to the guiding map; only the obstacles; or all but the
// guiding map (a flipbook's shell depth is uploaded into guide() instead).
enum class FrameStages { All, UpToGuide, ObstaclesOnly, AllButGuide };

class RealtimeFrame {
 public:
  // `shadowTiles`: the shadow atlas's tiles (0: no shadows); `guide`: the guiding map's settings (a lightmap
  // source's, LightmapSource::guide).
  RealtimeFrame(const gpu::Context& context, const gpu::PipelineCache& cache, const scene::Scene& scene,
                FrameTarget target, uint32_t shadowTiles, const render::GuideSettings& guide);

  // Records the passes for `volume` into `sequence`; `lightmaps` records what fills lightmaps() between the
  // guiding map and the shading (nothing: the caller uploads them before each submission). With an engine
  // target the shading is left out: recordComposite records it, per target.
  void record(gpu::Sequence& sequence, const render::Volume& volume, FrameStages stages,
              const std::function<void(gpu::Sequence&)>& lightmapStage);
  // The shading into the engine target of this frame (after setEngineTarget).
  void recordComposite(gpu::Sequence& sequence);
  // An engine's target: this frame's images and viewport. std::invalid_argument for a colour format other
  // than the one the frame was made for, a depth image that is not a depth format of the colour's size, or
  // a viewport outside the images.
  void setEngineTarget(EngineTarget target);
  bool drawsIntoEngineTarget() const { return engineFormat_.has_value() || insideRendering_; }
  // Inside an engine's rendering: this frame's depth buffer and size. std::invalid_argument for a depth image
  // that is not a depth format of that size, a layout it cannot be sampled in, or a viewport outside.
  void setInsideTarget(InsideTarget target);
  // The shading's values of this frame into `commands` (outside a render pass, followed by a full barrier),
  // then, inside the engine's rendering, its draw.
  void recordShadingParameters(VkCommandBuffer commands) const;
  void recordCompositeInside(VkCommandBuffer commands) const;
  // What a composite recording depends on: the target's images, size and viewport.
  std::vector<uint64_t> engineTargetKey() const;

  // This frame's scene: obstacles at `seconds`, the lights, the image-plane rectangle the target covers
  // (unset: fullFrame) and what the target's depth buffer holds (unset: the obstacle pass's depth, drawn
  // over boxDepthRange of the scene bounds).
  void updateScene(const render::Camera& camera, const std::vector<scene::Light>& lights, double seconds,
                   const std::optional<render::ImagePlane>& plane = std::nullopt,
                   std::optional<render::DepthMapping> targetDepth = std::nullopt);
  // This frame's billboard over `volumeBox` (billboardBounds) and the guide's values for it, at frame
  // `index`.
  render::ImagePlane updateGuide(const render::Camera& camera, const render::Box& volumeBox, int index);
  // The shading's values, for the billboard the lightmaps cover (whose world corners are then
  // billboardCorners().
  void updateShading(const render::Camera& camera, const std::vector<scene::Light>& lights,
                     const render::ImagePlane& billboard, const render::Box& volumeBox);

  const gpu::Image& color() const { return engine_ ? engine_->color : color_; }
  const gpu::Image& depth() const { return engine_ ? engine_->depth : depth_; }
  gpu::Image& guide() { return guide_; }
  const gpu::Image& guide() const { return guide_; }
  // The guide's emission (GuideSettings::emission), or nullptr.
  const gpu::Image* guideEmission() const { return guideEmission_ ? &*guideEmission_ : nullptr; }
  render::LightmapImages& lightmaps() { return lightmaps_; }
  const render::LightmapImages& lightmaps() const { return lightmaps_; }
  render::ObstacleMeshes& meshes() { return *meshes_; }
  const render::ObstacleMeshes& meshes() const { return *meshes_; }
  // The meshes of another set of obstacles (an engine's, sim::Simulation::setObstacles) for the passes
  // recorded from now on; returns the old ones, which frames in flight may still draw.
  std::unique_ptr<render::ObstacleMeshes> replaceObstacles(std::unique_ptr<render::ObstacleMeshes> meshes);
  const render::GuidingMap& guiding() const { return guiding_; }
  render::GuidingMap& guiding() { return guiding_; }
  // The camera's image in pixels: the own target, or the engine target's viewport.
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  uint32_t lightmapSize() const { return lightmapSize_; }
  uint32_t maxLights() const { return shading_.maxLights(); }  // per frame
  // The quad the shading draws, in the world: bottom-left, bottom-right, top-right, top-left.
  const std::array<glm::vec3, 4>& billboardCorners() const { return billboardCorners_; }
  // Notes of the last updateScene() for the user (e.g. a light without a shadow map).
  std::vector<std::string> takeNotes() { return shadowMaps_.takeNotes(); }

 private:
  void recordShading(gpu::Sequence& sequence, const std::optional<VkRect2D>& viewport);

  const scene::Scene* scene_;
  uint32_t width_ = 0, height_ = 0, lightmapSize_;
  std::optional<VkFormat> engineFormat_;
  std::optional<EngineTarget> engine_;
  bool insideRendering_;
  std::optional<InsideTarget> inside_;
  gpu::Image color_, depth_, guide_;
  std::optional<gpu::Image> guideEmission_;
  render::LightmapImages lightmaps_;
  std::unique_ptr<render::ObstacleMeshes> meshes_;
  render::ShadowMaps shadowMaps_;
  std::unique_ptr<render::ObstaclePass> obstacles_;  // sixway's own target only
  render::GuidingMap guiding_;
  render::SixWayShading shading_;
  render::ShadingControls controls_;
  render::ImagePlane frame_;
  render::DepthMapping targetDepth_;
  std::array<glm::vec3, 4> billboardCorners_{};
};

}  // namespace sixway::runtime
