#pragma once
// The obstacles in the image (docs/conventions.md, "The frame"): the obstacle meshes rasterized through the
// camera with diffuse shading under the scene's lights (shadowed by the obstacles through the shadow maps)
// and ambient, into a colour image (RGBA16F, premultiplied: alpha 1 where an obstacle is, the background with
// alpha 0 elsewhere) and a depth image (D32, render::projectionMatrix of the scene depth range) of the whole
// frame. Per-frame values travel in a uniform buffer, so the pass is recorded once; the obstacles' positions
// come from ObstacleMeshes::update. Shaders: shaders/render/obstacle.{vert,frag}.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <span>

#include "gpu/buffer.h"
#include "render/camera.h"
#include "render/projection.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Context;
class Image;
class Pipeline;
class PipelineCache;
class Sampler;
class Sequence;
}  // namespace sixway::gpu

namespace sixway::render {

class ObstacleMeshes;
class ShadowMaps;
struct Volume;

// Diffuse albedo of every obstacle: a mid grey, so that lit faces stay well inside [0, 1] under the shipped
// scenes' lights (irradiance π: radiance 0.6).
inline constexpr glm::vec3 kObstacleAlbedo{0.6f};

class ObstaclePass {
 public:
  static constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
  static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

  // `background` (the scene's render.background) is the clear colour, with alpha 0.
  ObstaclePass(const gpu::Context& context, const gpu::PipelineCache& cache, glm::vec3 background);
  ~ObstaclePass();

  // Per frame: the camera, the rectangle of its image plane that the targets cover (fullFrame), the depth
  // range of the depth buffer (boxDepthRange of sceneBounds), the lights as they are this frame
  // (sceneLights), the ambient light and the shadow maps, updated for this frame (their tiles and light
  // matrices). Throws io::InputError for more lights than the shader takes (8).
  void update(const Camera& camera, const ImagePlane& plane, DepthRange range,
              std::span<const scene::Light> lights, const std::optional<scene::Ambient>& ambient,
              const ShadowMaps& shadows);

  // Stage "obstacles": clears `color` (kColorFormat, colour attachment) to the background and `depth`
  // (kDepthFormat, depth attachment) to 1, then draws the meshes, reading the shadow atlas (recorded
  // before, stage "shadow maps") and, when given, the smoke's density and optics, through which the light
  // reaches them (and the ambient light, along the normal). The images' sizes are the frame's.
  void record(gpu::Sequence& sequence, const ObstacleMeshes& meshes, const ShadowMaps& shadows,
              const gpu::Image& color, const gpu::Image& depth, const Volume* smoke = nullptr,
              const scene::Smoke& smokeOptics = {}) const;

  // Of the last update: world → clip space of the depth buffer.
  const glm::mat4& viewProjection() const { return viewProjection_; }

 private:
  glm::vec3 background_;
  std::unique_ptr<gpu::Pipeline> pipeline_;
  std::unique_ptr<gpu::Sampler> nearest_;
  gpu::Buffer params_;
  gpu::Buffer noSmoke_;  // bound in place of a density buffer when there is no smoke
  glm::mat4 viewProjection_{1.0f};
};

}  // namespace sixway::render
