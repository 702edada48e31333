#pragma once
// Six-way shading of the smoke billboard (docs/conventions.md, "Shading"): a graphics pass that draws the
// camera-facing quad over the lightmaps' rectangle and blends the lit smoke premultiplied-over onto a colour
// target that already holds the background and the obstacles. Any number of directional and point lights
// (colour, intensity, obstacle shadows from a shadow atlas, tested at the smoke shell), ambient light
// (constant or L1 spherical harmonics), emission through a colour gradient, Unity's colour/absorption and
// lightmap remapping controls, and depth-aware compositing against the obstacles' depth buffer. The same pass
// shades neural lightmaps, reference lightmaps and flipbook frames. Formulas and conventions:
// docs/real-time-rendering.md, "Six-way shading"; shaders: shaders/render/billboard.vert, sixway_shade.frag,
// shaders/common/sixway_lighting.glsl, shadow.glsl.
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/image.h"
#include "gpu/sequence.h"
#include "render/camera.h"
#include "render/projection.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Context;
class Pipeline;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::render {

// One light as the shader sees it.
struct ShadingLight {
  enum class Type { Directional, Point };
  Type type = Type::Directional;
  glm::vec3 vector{0.0f, 1.0f, 0.0f};  // directional: unit direction toward the light; point: its position
  glm::vec3 radiance{3.14159265f};     // colour · intensity: irradiance (directional) or radiant intensity
  int shadowTile = -1;                 // tile of the shadow atlas holding its shadow map; −1: no shadow
  glm::mat4 shadowMatrix{1.0f};        // world → the light's clip space (the view-projection of its tile)
};

// The scene's light (positioned for the frame, see sceneLights) with its shadow map, if any.
ShadingLight shadingLight(const scene::Light& light, int shadowTile = -1,
                          const glm::mat4& shadowMatrix = glm::mat4(1.0f));

// Unity's "Lightmap Remap" range: straight (not premultiplied) values in [inMin, inMax] map onto
// [outMin, outMax] (clamped at the input ends, at least 0).
struct RemapRange {
  float inMin = 0.0f, inMax = 1.0f, outMin = 0.0f, outMax = 1.0f;
};

// A key of the emissive gradient: the colour at an emissive-channel value (position > 0).
struct GradientKey {
  float position = 1.0f;
  glm::vec3 color{1.0f};
};

constexpr int kMaxGradientKeys = 16;   // shaders/common/sixway_lighting.glsl
constexpr float kMaxPcfRadius = 4.0f;  // texels, shaders/common/shadow.glsl

// Unity's artistic controls. The defaults (no tint, no remapping, white emission) shade reference lightmaps
// to the physically meaningful result.
struct ShadingControls {
  glm::vec3 color{1.0f};            // tint (plain multiply) or, with absorption, the absorption colour
  bool absorption = false;          // Unity's colour absorption mode instead of the tint
  float absorptionStrength = 1.0f;  // 0..1; range r = (1 − 1/π)·strength + 1/π
  std::optional<RemapRange> lightmapRemap;  // applied to the six light channels
  std::optional<RemapRange> alphaRemap;     // applied to alpha; the premultiplied channels follow
  // Emissive colour = multiplier · gradient(emissive channel): linear between keys (increasing positions),
  // from black at 0 to the first key, proportional beyond the last. Empty: one white key at 1, i.e. the
  // channel value as grey.
  std::vector<GradientKey> emissiveGradient;
  float emissiveMultiplier = 1.0f;
  // Set (> 0) for lightmaps that sixway bakes or predicts, whose emissive channel is premultiplied luminance:
  // the gradient is looked up at the channel's straight value e / (alpha · s) instead, and its colour scaled
  // by alpha · s. With s = emission intensity / extinction that value is the absorption-weighted mean
  // luminance of the ramp along the ray, so the hue follows the smoke's temperature rather than its
  // thickness, and the luminance stays e. Unset: Unity's gradient(e), for emissive masks.
  std::optional<float> emissiveStraightScale;
};

// The default gradient for a scene's emission: the ramp's colours placed at their own luminance (keys that
// are not brighter than the one before are dropped), so the emissive colour has exactly the luminance the
// baker wrote into the emissive channel, and, looked up at the straight value (emissiveStraightScale), the
// ramp's colour of that luminance. Empty for no emission.
std::vector<GradientKey> emissiveGradientFromRamp(const scene::Emission& emission);
// emissiveStraightScale for a scene's smoke: intensity / extinction, the emitted luminance of opaque smoke
// per unit of ramp luminance (the source function j/σ_t of shaders/render/sixway_march.comp). None without
// emission.
std::optional<float> emissiveStraightScale(const scene::Smoke& smoke);

// The obstacle shadow maps: one D32 depth image, `tileSize` wide, a vertical stack of square tiles, tile t
// holding the light with shadowTile t (docs/real-time-rendering.md, "Obstacles and shadows").
struct ShadowAtlas {
  const gpu::Image* depth = nullptr;  // none: every light is unshadowed
  uint32_t tileSize = 0;
  float pcfRadiusTexels = 1.5f;  // half-width of the PCF box, 0..kMaxPcfRadius (0: one texel)
  float depthBias = 0.002f;      // subtracted from the point's depth (depth-buffer units) before comparing
};

// The attachments of the rendering the shading draws in: the smoke goes "over" colour attachment 0, the
// others are not written; depth and stencil: the rendering's (UNDEFINED: none), never written.
struct ShadingTargetFormats {
  std::vector<VkFormat> colors;
  VkFormat depth = VK_FORMAT_UNDEFINED, stencil = VK_FORMAT_UNDEFINED;
};

class SixWayShading {
 public:
  // `colorFormat`: the format of the colour targets it will draw into.
  SixWayShading(const gpu::Context& context, const gpu::PipelineCache& cache, VkFormat colorFormat,
                uint32_t maxLights = 16);
  // For drawing inside a rendering of these formats (recordInside). std::invalid_argument without a colour.
  SixWayShading(const gpu::Context& context, const gpu::PipelineCache& cache,
                const ShadingTargetFormats& formats, uint32_t maxLights = 16);
  ~SixWayShading();

  // The frame's values; call before each submission of the recorded sequence. `frame`: the image-plane
  // rectangle the colour target covers; `billboard`: the lightmaps' rectangle; `shellRange`: the view depths
  // the guide's shell depth is encoded in (boxDepthRange of the volume box); `sceneDepth`: what the
  // obstacle depth buffer holds. Throws io::InputError (source "shading") for more lights than maxLights
  // and for controls out of range.
  void update(const Camera& camera, const ImagePlane& frame, const ImagePlane& billboard,
              DepthRange shellRange, DepthMapping sceneDepth, std::span<const ShadingLight> lights,
              const std::optional<scene::Ambient>& ambient, const ShadingControls& controls);

  // Records the draw (timed stage "shade"). Lightmaps A and B: sampled float RGBA images over the billboard;
  // `guide`: the guiding map (shell depth in B), none: no pixel has a shell; `opacityDepths`: where the
  // smoke's opacity builds up (GuidingMap::opacityDepths), none: the smoke is a card at the shell depth;
  // `obstacleDepth`: D32, the colour target's size, none: nothing hides the smoke; `viewport`: the
  // rectangle of the colour target that the frame's image plane covers (the draw's viewport and scissor),
  // none: the whole target. Throws std::invalid_argument for images that do not fit and a viewport outside
  // the target.
  void record(gpu::Sequence& sequence, const gpu::Image& lightmapA, const gpu::Image& lightmapB,
              const gpu::Image* guide, const gpu::Image* opacityDepths, const gpu::Image* obstacleDepth,
              const ShadowAtlas& shadows, const gpu::Image& colorTarget,
              const std::optional<VkRect2D>& viewport = std::nullopt) const;

  // Inside a rendering the caller began (primary or secondary command buffer) with the formats this shading
  // was made for, `target` in size: the same draw without a stage, its own rendering or barriers. The
  // frame's values must be in place: recordParameters, outside the rendering, before it in queue order.
  // `obstacleDepth` (SAMPLED, a depth view) is in `obstacleDepthLayout` there: a read-only depth layout or
  // GENERAL when it is also the rendering's depth attachment.
  void recordInside(VkCommandBuffer commands, const gpu::Image& lightmapA, const gpu::Image& lightmapB,
                    const gpu::Image* guide, const gpu::Image* opacityDepths, const gpu::Image& obstacleDepth,
                    VkImageLayout obstacleDepthLayout, const ShadowAtlas& shadows, VkExtent2D target,
                    const std::optional<VkRect2D>& viewport) const;
  // The values of the last update() into `commands` (outside a render pass); the caller orders them before
  // the draw that reads them (e.g. a full barrier).
  void recordParameters(VkCommandBuffer commands) const;

  uint32_t maxLights() const { return maxLights_; }

 private:
  gpu::Draw quad(const gpu::Image& lightmapA, const gpu::Image& lightmapB, const gpu::Image* guide,
                 const gpu::Image* opacityDepths, const gpu::Image* obstacleDepth,
                 VkImageLayout obstacleDepthLayout, const ShadowAtlas& shadows, VkExtent2D target,
                 const std::optional<VkRect2D>& viewport) const;

  const gpu::Context* context_;
  uint32_t maxLights_;
  std::unique_ptr<gpu::Pipeline> pipeline_;
  std::unique_ptr<gpu::Sampler> linear_, nearest_;
  gpu::Buffer params_, lights_;
  gpu::Image noGuide_, noDepth_;  // 1×1 stand-ins: no shell (B = 1), depth 1
};

}  // namespace sixway::render
