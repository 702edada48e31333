#include "render/sixway_shading.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <stdexcept>
#include <string>

#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/draw_commands.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "io/error.h"
#include "render/billboard.h"
#include "render/gpu_layout.h"

namespace sixway::render {
namespace {

constexpr float kPi = 3.14159265358979f;

// Mirrors ShadeParams in shaders/render/sixway_shade_params.glsl (every member 16 bytes wide:
// render/gpu_layout.h).
struct ShadeParams {
  layout::CameraRays camera;
  glm::vec4 frameToBillboard;
  glm::vec4 depths;
  glm::vec4 clipCorners[4];
  glm::vec4 color;
  glm::vec4 lightmapRemap;
  glm::vec4 alphaRemap;
  glm::vec4 misc;
  glm::ivec4 counts;
  glm::vec4 ambient[4];
  glm::vec4 gradient[kMaxGradientKeys];
};
static_assert(sizeof(ShadeParams) == 16 * (5 + 2 + 4 + 5 + 4 + kMaxGradientKeys));

// Mirrors ShadeLight (std430).
struct ShadeLight {
  glm::vec4 vector;
  glm::vec4 radiance;
  glm::mat4 shadowMatrix;
};
static_assert(sizeof(ShadeLight) == 96);

// Mirrors ShadePush.
struct ShadePush {
  glm::ivec4 frame;
  glm::ivec4 atlas;
  glm::vec4 shadow;
  glm::ivec4 viewport;
};

enum Flags : int { kAbsorption = 1, kLightmapRemap = 2, kAlphaRemap = 4 };

float luminance(glm::vec3 c) {
  return glm::dot(c, glm::vec3(0.2126f, 0.7152f, 0.0722f));
}

void checkRemap(const RemapRange& r, const char* what) {
  if (!(r.inMax > r.inMin))
    throw io::InputError("shading", std::string(what) + " remap needs inMax > inMin (got " +
                                        std::to_string(r.inMin) + ", " + std::to_string(r.inMax) + ")");
}

void checkControls(const ShadingControls& c) {
  if (!(c.color.r >= 0.0f && c.color.g >= 0.0f && c.color.b >= 0.0f))
    throw io::InputError("shading", "the tint/absorption colour must be >= 0");
  if (!(c.absorptionStrength >= 0.0f && c.absorptionStrength <= 1.0f))
    throw io::InputError("shading", "the absorption strength must be in [0, 1] (got " +
                                        std::to_string(c.absorptionStrength) + ")");
  if (c.lightmapRemap) checkRemap(*c.lightmapRemap, "the lightmap");
  if (c.alphaRemap) checkRemap(*c.alphaRemap, "the alpha");
  if (c.emissiveGradient.size() > kMaxGradientKeys)
    throw io::InputError("shading", "the emissive gradient has " + std::to_string(c.emissiveGradient.size()) +
                                        " keys; at most " + std::to_string(kMaxGradientKeys));
  float previous = 0.0f;
  for (const GradientKey& key : c.emissiveGradient) {
    if (!(key.position > previous))
      throw io::InputError("shading", "emissive gradient positions must be > 0 and strictly increasing");
    previous = key.position;
  }
  if (!(c.emissiveMultiplier >= 0.0f))
    throw io::InputError("shading", "the emissive multiplier must be >= 0");
  if (c.emissiveStraightScale &&
      !(*c.emissiveStraightScale > 0.0f && std::isfinite(*c.emissiveStraightScale)))
    throw io::InputError("shading", "the emissive straight scale must be a positive number");
}

// L0 and L1 of the ambient radiance, L1 turned into the six-way frame (camera right, up, forward).
void ambientCoefficients(const std::optional<scene::Ambient>& ambient, const Camera& camera,
                         glm::vec4 (&out)[4]) {
  for (glm::vec4& c : out) c = glm::vec4(0.0f);
  if (!ambient) return;
  if (const auto* constant = std::get_if<scene::AmbientColor>(&*ambient)) {
    out[0] = glm::vec4(constant->color, 0.0f);
    return;
  }
  const auto& sh = std::get<scene::AmbientSh>(*ambient).coefficients;
  out[0] = glm::vec4(sh[0], 0.0f);
  const glm::vec3 axes[3] = {camera.right, camera.up, camera.forward};
  for (int i = 0; i < 3; ++i)  // per colour: L1 (a world vector) · axis
    out[i + 1] = glm::vec4(sh[1] * axes[i].x + sh[2] * axes[i].y + sh[3] * axes[i].z, 0.0f);
}

void requireSampledFloat(const gpu::Image& image, const char* what) {
  if (image.desc().depth != 1 || gpu::isDepthFormat(image.desc().format) ||
      !(image.desc().usage & VK_IMAGE_USAGE_SAMPLED_BIT))
    throw std::invalid_argument(std::string("six-way shading: ") + what +
                                " must be a sampled 2D colour image");
}

}  // namespace

ShadingLight shadingLight(const scene::Light& light, int shadowTile, const glm::mat4& shadowMatrix) {
  ShadingLight s;
  if (const auto* directional = std::get_if<scene::DirectionalLight>(&light.source)) {
    s.type = ShadingLight::Type::Directional;
    s.vector = glm::normalize(directional->direction);
  } else {
    s.type = ShadingLight::Type::Point;
    s.vector = std::get<scene::PointLight>(light.source).position;
  }
  s.radiance = light.color * light.intensity;
  s.shadowTile = light.shadows ? shadowTile : -1;
  s.shadowMatrix = shadowMatrix;
  return s;
}

std::vector<GradientKey> emissiveGradientFromRamp(const scene::Emission& emission) {
  std::vector<GradientKey> keys;
  if (emission.intensity <= 0.0f) return keys;
  for (const scene::EmissionKey& k : emission.ramp) {
    const float l = luminance(k.color);
    if (l > (keys.empty() ? 0.0f : keys.back().position)) keys.push_back({l, k.color});
  }
  return keys;
}

std::optional<float> emissiveStraightScale(const scene::Smoke& smoke) {
  if (smoke.emission.intensity <= 0.0f) return std::nullopt;
  return smoke.emission.intensity / smoke.extinction;
}

SixWayShading::SixWayShading(const gpu::Context& context, const gpu::PipelineCache& cache,
                             VkFormat colorFormat, uint32_t maxLights)
    : SixWayShading(context, cache, ShadingTargetFormats{{colorFormat}}, maxLights) {}

SixWayShading::SixWayShading(const gpu::Context& context, const gpu::PipelineCache& cache,
                             const ShadingTargetFormats& formats, uint32_t maxLights)
    : context_(&context),
      maxLights_(maxLights),
      linear_(std::make_unique<gpu::Sampler>(context, VK_FILTER_LINEAR)),
      nearest_(std::make_unique<gpu::Sampler>(context, VK_FILTER_NEAREST)),
      params_(context, sizeof(ShadeParams), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
              gpu::MemoryKind::FrameParameters, "six-way shading parameters"),
      lights_(context, std::max<uint32_t>(maxLights, 1) * sizeof(ShadeLight),
              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryKind::FrameParameters, "six-way shading lights"),
      noGuide_(context, {1, 1, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT, "no guide"}),
      noDepth_(context, {1, 1, 1, VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT, "no depth"}) {
  if (formats.colors.empty())
    throw std::invalid_argument("six-way shading: no colour attachment to draw into");
  if (formats.colors.size() > 1 && !context.capabilities().independentBlend)
    throw gpu::GpuError("six-way shading: a rendering with " + std::to_string(formats.colors.size()) +
                        " colour attachments needs the device's independentBlend feature (the smoke blends "
                        "into the first, the others are masked)");
  using gpu::BindingType;
  gpu::GraphicsPipelineDesc desc;
  desc.vertexShader = "render/billboard.vert";
  desc.fragmentShader = "render/sixway_shade.frag";
  desc.bindings = {BindingType::StorageBuffer, BindingType::StorageBuffer, BindingType::SampledImage,
                   BindingType::SampledImage,  BindingType::SampledImage,  BindingType::SampledImage,
                   BindingType::SampledImage,  BindingType::SampledImage};
  desc.pushConstantBytes = sizeof(ShadePush);
  desc.colorFormats = formats.colors;
  desc.colorsWritten = 1;
  desc.depthFormat = formats.depth;
  desc.stencilFormat = formats.stencil;
  desc.blend = gpu::Blend::PremultipliedOver;
  pipeline_ = std::make_unique<gpu::Pipeline>(context, cache, desc);

  const float noShell[4] = {0.0f, 0.0f, 1.0f, 0.0f}, far = 1.0f;
  noGuide_.upload(std::as_bytes(std::span(noShell)));
  noDepth_.upload(std::as_bytes(std::span(&far, 1)));
}

SixWayShading::~SixWayShading() = default;

void SixWayShading::update(const Camera& camera, const ImagePlane& frame, const ImagePlane& billboard,
                           DepthRange shellRange, DepthMapping sceneDepth,
                           std::span<const ShadingLight> lights, const std::optional<scene::Ambient>& ambient,
                           const ShadingControls& controls) {
  if (lights.size() > maxLights_)
    throw io::InputError("shading", std::to_string(lights.size()) +
                                        " lights; the six-way shading takes at most " +
                                        std::to_string(maxLights_));
  checkControls(controls);

  ShadeParams p{};
  p.camera = layout::cameraRays(camera, frame);
  // In double, so that a billboard equal to the frame maps pixel centres exactly onto texel centres.
  const glm::dvec2 fMin(frame.min), fSize = glm::dvec2(frame.max) - fMin;
  const glm::dvec2 bMin(billboard.min), bMax(billboard.max), bSize = bMax - bMin;
  p.frameToBillboard = glm::vec4(fSize.x / bSize.x, fSize.y / bSize.y, (fMin.x - bMin.x) / bSize.x,
                                 (bMax.y - (fMin.y + fSize.y)) / bSize.y);
  const float offset = float(sceneDepth.offset);
  p.depths = glm::vec4(shellRange.near, shellRange.far, offset, float(sceneDepth.scale));
  // The quad halfway through the volume's depth range (no depth attachment: only its footprint matters).
  const float depth = 0.5f * (shellRange.near + shellRange.far);
  const glm::mat4 viewProjection = projectionMatrix(frame, shellRange) * viewMatrix(camera);
  const auto corners = billboardCorners(camera, billboard, depth);
  for (int i = 0; i < 4; ++i) p.clipCorners[i] = viewProjection * glm::vec4(corners[i], 1.0f);
  p.color = glm::vec4(controls.color, (1.0f - 1.0f / kPi) * controls.absorptionStrength + 1.0f / kPi);
  const RemapRange identity;
  const RemapRange& lm = controls.lightmapRemap.value_or(identity);
  const RemapRange& am = controls.alphaRemap.value_or(identity);
  p.lightmapRemap = glm::vec4(lm.inMin, lm.inMax, lm.outMin, lm.outMax);
  p.alphaRemap = glm::vec4(am.inMin, am.inMax, am.outMin, am.outMax);
  p.misc = glm::vec4(depth, controls.emissiveMultiplier, controls.emissiveStraightScale.value_or(0.0f),
                     float(sceneDepth.offset - double(offset)));
  std::vector<GradientKey> gradient = controls.emissiveGradient;
  if (gradient.empty()) gradient.push_back({1.0f, glm::vec3(1.0f)});
  for (size_t k = 0; k < gradient.size(); ++k)
    p.gradient[k] = glm::vec4(gradient[k].position, gradient[k].color);
  p.counts =
      glm::ivec4(int(lights.size()), int(gradient.size()),
                 (controls.absorption ? kAbsorption : 0) | (controls.lightmapRemap ? kLightmapRemap : 0) |
                     (controls.alphaRemap ? kAlphaRemap : 0),
                 0);
  ambientCoefficients(ambient, camera, p.ambient);
  params_.upload(std::as_bytes(std::span(&p, 1)));

  std::vector<ShadeLight> packed;
  for (const ShadingLight& l : lights)
    packed.push_back({glm::vec4(l.vector, l.type == ShadingLight::Type::Point ? 1.0f : 0.0f),
                      glm::vec4(l.radiance, float(l.shadowTile < 0 ? -1 : l.shadowTile)), l.shadowMatrix});
  if (!packed.empty()) lights_.upload(std::as_bytes(std::span(packed)));
}

gpu::Draw SixWayShading::quad(const gpu::Image& lightmapA, const gpu::Image& lightmapB,
                              const gpu::Image* guide, const gpu::Image* opacityDepths,
                              const gpu::Image* obstacleDepth, VkImageLayout obstacleDepthLayout,
                              const ShadowAtlas& shadows, VkExtent2D target,
                              const std::optional<VkRect2D>& viewport) const {
  requireSampledFloat(lightmapA, "lightmap A");
  requireSampledFloat(lightmapB, "lightmap B");
  if (guide) requireSampledFloat(*guide, "the guide");
  if (opacityDepths) requireSampledFloat(*opacityDepths, "the opacity depths");
  if (obstacleDepth &&
      (!gpu::isDepthFormat(obstacleDepth->desc().format) || obstacleDepth->desc().width != target.width ||
       obstacleDepth->desc().height != target.height))
    throw std::invalid_argument(
        "six-way shading: the obstacle depth must be a depth format (D16, D24, D32) of the colour target's "
        "size");
  uint32_t tiles = 0;
  if (shadows.depth) {
    const auto& atlas = shadows.depth->desc();
    if (atlas.format != VK_FORMAT_D32_SFLOAT || shadows.tileSize == 0 || atlas.width != shadows.tileSize ||
        atlas.height % shadows.tileSize != 0)
      throw std::invalid_argument(
          "six-way shading: the shadow atlas must be D32, tileSize wide, a stack of tiles");
    if (!(shadows.pcfRadiusTexels >= 0.0f && shadows.pcfRadiusTexels <= kMaxPcfRadius))
      throw std::invalid_argument("six-way shading: the PCF radius must be in [0, 4] texels");
    tiles = atlas.height / shadows.tileSize;
  }

  const VkRect2D area = viewport.value_or(VkRect2D{{0, 0}, target});
  if (area.offset.x < 0 || area.offset.y < 0 || area.extent.width == 0 || area.extent.height == 0 ||
      area.offset.x + area.extent.width > target.width || area.offset.y + area.extent.height > target.height)
    throw std::invalid_argument(
        "six-way shading: the viewport must be a non-empty rectangle inside the target");
  const ShadePush push{glm::ivec4(0, 0, obstacleDepth ? 1 : 0, opacityDepths ? 1 : 0),
                       glm::ivec4(shadows.depth ? shadows.tileSize : 0, tiles, 0, 0),
                       glm::vec4(shadows.pcfRadiusTexels, shadows.depthBias, 0.0f, 0.0f),
                       glm::ivec4(area.offset.x, area.offset.y, area.extent.width, area.extent.height)};
  return gpu::Draw{pipeline_.get(),
                   {gpu::reads(params_), gpu::reads(lights_), gpu::samples(lightmapA, *linear_),
                    gpu::samples(lightmapB, *linear_), gpu::samples(guide ? *guide : noGuide_, *nearest_),
                    obstacleDepth ? gpu::samples(*obstacleDepth, *nearest_, obstacleDepthLayout)
                                  : gpu::samples(noDepth_, *nearest_),
                    gpu::samples(shadows.depth ? *shadows.depth : noDepth_, *nearest_),
                    gpu::samples(opacityDepths ? *opacityDepths : noGuide_, *nearest_)},
                   gpu::pushBytes(push),
                   nullptr,
                   nullptr,
                   6,
                   1,
                   area};
}

void SixWayShading::record(gpu::Sequence& sequence, const gpu::Image& lightmapA, const gpu::Image& lightmapB,
                           const gpu::Image* guide, const gpu::Image* opacityDepths,
                           const gpu::Image* obstacleDepth, const ShadowAtlas& shadows,
                           const gpu::Image& colorTarget, const std::optional<VkRect2D>& viewport) const {
  const gpu::Draw draw =
      quad(lightmapA, lightmapB, guide, opacityDepths, obstacleDepth, VK_IMAGE_LAYOUT_GENERAL, shadows,
           {colorTarget.desc().width, colorTarget.desc().height}, viewport);
  sequence.beginStage("shade");
  sequence.render({{&colorTarget}, nullptr, std::nullopt, std::nullopt}, std::span(&draw, 1));
  sequence.endStage();
}

void SixWayShading::recordParameters(VkCommandBuffer commands) const {
  const gpu::Buffer* buffers[] = {&params_, &lights_};
  gpu::recordParameterUpdates(commands, buffers);
}

void SixWayShading::recordInside(VkCommandBuffer commands, const gpu::Image& lightmapA,
                                 const gpu::Image& lightmapB, const gpu::Image* guide,
                                 const gpu::Image* opacityDepths, const gpu::Image& obstacleDepth,
                                 VkImageLayout obstacleDepthLayout, const ShadowAtlas& shadows,
                                 VkExtent2D target, const std::optional<VkRect2D>& viewport) const {
  gpu::recordDraw(*context_, commands,
                  quad(lightmapA, lightmapB, guide, opacityDepths, &obstacleDepth, obstacleDepthLayout,
                       shadows, target, viewport),
                  target);
}

}  // namespace sixway::render
