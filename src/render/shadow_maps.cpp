#include "render/shadow_maps.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <utility>
#include <variant>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "io/error.h"
#include "render/obstacle_meshes.h"
#include "render/projection.h"

namespace sixway::render {
namespace {

// Texels kept free around the casters' projection on each side of a tile: more than the widest filter of
// shaders/common/shadow.glsl (kMaxPcfRadius = 4), so that filtering never reaches a caster through the
// clamped tile edge.
constexpr float kBorderTexels = 6.0f;
// The depth range is widened by this fraction of its span on both sides, so that faces lying exactly on the
// bounds are not clipped by rounding.
constexpr float kDepthMargin = 0.005f;

struct Frame {
  glm::vec3 right, up, forward;  // right × up = −forward, as a render::Camera
};

Frame frameLookingAlong(glm::vec3 forward) {
  const glm::vec3 hint = std::abs(forward.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
  const glm::vec3 right = glm::normalize(glm::cross(forward, hint));
  return {right, glm::cross(right, forward), forward};
}

std::array<glm::vec3, 8> corners(const Box& b) {
  std::array<glm::vec3, 8> c;
  for (int i = 0; i < 8; ++i)
    c[i] = glm::vec3((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z);
  return c;
}

struct Range {
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  void add(float x) {
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  // Grown so that the old span covers the tile less kBorderTexels on each side.
  Range bordered(uint32_t tileSize) const {
    const float span = std::max(hi - lo, 1e-6f);
    const float pad = span * kBorderTexels / std::max(float(tileSize) - 2.0f * kBorderTexels, 1.0f);
    return {lo - pad, hi + pad};
  }
  Range margined() const {
    const float pad = kDepthMargin * std::max(hi - lo, 1e-6f);
    return {lo - pad, hi + pad};
  }
};

// Orthographic along the light: the casters' extent across the beam onto [-1, 1] (with a border), depth from
// the casters' nearest corner to the scene's farthest onto [0, 1].
glm::mat4 directionalProjection(glm::vec3 towardLight, const Box& casters, const Box& scene,
                                uint32_t tileSize) {
  const Frame f = frameLookingAlong(-glm::normalize(towardLight));
  Range x, y, z;
  for (glm::vec3 c : corners(casters)) {
    x.add(glm::dot(c, f.right));
    y.add(glm::dot(c, f.up));
    z.add(glm::dot(c, f.forward));
  }
  for (glm::vec3 c : corners(scene)) z.add(glm::dot(c, f.forward));
  x = x.bordered(tileSize), y = y.bordered(tileSize), z = z.margined();
  glm::mat4 m(0.0f);  // m[column][row]
  const auto row = [&](int r, glm::vec3 axis, float scale, float offset) {
    for (int k = 0; k < 3; ++k) m[k][r] = axis[k] * scale;
    m[3][r] = offset;
  };
  row(0, f.right, 2.0f / (x.hi - x.lo), -(x.hi + x.lo) / (x.hi - x.lo));
  row(1, f.up, 2.0f / (y.hi - y.lo), -(y.hi + y.lo) / (y.hi - y.lo));
  row(2, f.forward, 1.0f / (z.hi - z.lo), -z.lo / (z.hi - z.lo));
  m[3][3] = 1.0f;
  return m;
}

// Perspective from the light toward the casters' centre: the image-plane rectangle holding the casters'
// projected corners (it holds the projected box, their convex hull; with a border), depth from the casters'
// nearest corner to the scene's farthest. None unless the casters' box lies wholly in front of the light.
std::optional<glm::mat4> pointProjection(glm::vec3 position, const Box& casters, const Box& scene,
                                         uint32_t tileSize) {
  const glm::vec3 toCasters = casters.centre() - position;
  if (!(glm::length(toCasters) > 0.0f)) return std::nullopt;
  const Frame f = frameLookingAlong(glm::normalize(toCasters));
  Range x, y, z;
  for (glm::vec3 c : corners(casters)) z.add(glm::dot(c - position, f.forward));
  for (glm::vec3 c : corners(scene)) z.hi = std::max(z.hi, glm::dot(c - position, f.forward));
  if (!(z.lo > 1e-3f * z.hi)) return std::nullopt;
  for (glm::vec3 c : corners(casters)) {
    const glm::vec3 d = c - position;
    const float depth = glm::dot(d, f.forward);
    x.add(glm::dot(d, f.right) / depth);
    y.add(glm::dot(d, f.up) / depth);
  }
  x = x.bordered(tileSize), y = y.bordered(tileSize);
  const Range depth{z.lo * (1.0f - kDepthMargin), z.hi * (1.0f + kDepthMargin)};
  Camera eye;
  eye.position = position;
  eye.right = f.right;
  eye.up = f.up;
  eye.forward = f.forward;
  return projectionMatrix(ImagePlane{{x.lo, y.lo}, {x.hi, y.hi}}, DepthRange{depth.lo, depth.hi}) *
         viewMatrix(eye);
}

// Takes every vertex beyond the far plane: the tile of a light without a projection this frame stays empty.
glm::mat4 drawsNothing() {
  glm::mat4 m(0.0f);
  m[3] = glm::vec4(0.0f, 0.0f, 2.0f, 1.0f);
  return m;
}

}  // namespace

uint32_t shadowTileCount(std::span<const scene::Light> lights,
                         const std::vector<scene::Obstacle>& obstacles) {
  if (std::none_of(obstacles.begin(), obstacles.end(), [](const scene::Obstacle& o) { return o.shadows; }))
    return 0;
  return uint32_t(
      std::count_if(lights.begin(), lights.end(), [](const scene::Light& l) { return l.shadows; }));
}

std::optional<glm::mat4> shadowProjection(const scene::Light& light, const Box& casters, const Box& scene,
                                          uint32_t tileSize) {
  if (const auto* directional = std::get_if<scene::DirectionalLight>(&light.source))
    return directionalProjection(directional->direction, casters, scene, tileSize);
  return pointProjection(std::get<scene::PointLight>(light.source).position, casters, scene, tileSize);
}

ShadowMaps::ShadowMaps(const gpu::Context& context, const gpu::PipelineCache& cache, uint32_t tileSize,
                       uint32_t tiles)
    : tileSize_(tileSize), tiles_(tiles) {
  if (tileSize == 0) throw io::InputError("render", "the shadow map size must be at least 1 texel");
  const uint64_t height = uint64_t(tileSize) * tiles;
  const uint32_t limit = context.limits().maxImageDimension2D;
  if (tileSize > limit || height > limit)
    throw io::InputError("render", "the shadow atlas of " + std::to_string(tiles) + " tiles of " +
                                       std::to_string(tileSize) + "x" + std::to_string(tileSize) +
                                       " texels needs an image " + std::to_string(height) +
                                       " texels tall, more than this device's " + std::to_string(limit) +
                                       "; reduce the shadow map size or the number of shadow-casting lights");
  atlas_ = gpu::Image(
      context, {tiles ? tileSize : 1, tiles ? uint32_t(height) : 1, 1, VK_FORMAT_D32_SFLOAT,
                VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "shadow atlas"});
  matrices_ =
      gpu::Buffer(context, std::max(tiles, 1u) * sizeof(glm::mat4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                  gpu::MemoryKind::FrameParameters, "light view-projections");
  gpu::GraphicsPipelineDesc desc;
  desc.vertexShader = "render/shadow_depth.vert";
  desc.fragmentShader = "render/shadow_depth.frag";
  desc.bindings = {gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer};
  desc.pushConstantBytes = sizeof(uint32_t);
  desc.vertexStride = sizeof(ObstacleVertex);
  desc.attributes = ObstacleMeshes::vertexAttributes();
  desc.depthFormat = VK_FORMAT_D32_SFLOAT;
  desc.depthTest = desc.depthWrite = true;
  pipeline_ = std::make_unique<gpu::Pipeline>(context, cache, desc);
}

ShadowMaps::~ShadowMaps() = default;

void ShadowMaps::update(std::span<const scene::Light> lights, const Box& sceneBounds,
                        const ObstacleMeshes& meshes) {
  tileOf_.assign(lights.size(), -1);
  lightMatrices_.assign(lights.size(), drawsNothing());
  std::vector<glm::mat4> tileMatrices(std::max(tiles_, 1u), drawsNothing());
  if (meshes.casterIndexCount() > 0) {
    uint32_t next = 0;
    for (size_t i = 0; i < lights.size(); ++i) {
      if (!lights[i].shadows) continue;
      if (next == tiles_) {
        if (tiles_ > 0 && noted_.insert(i).second)
          notes_.push_back("lights[" + std::to_string(i) + "]: no shadow-atlas tile left (" +
                           std::to_string(tiles_) + "): drawn without obstacle shadows");
        continue;
      }
      const uint32_t tile = next++;
      const std::optional<glm::mat4> m =
          shadowProjection(lights[i], meshes.casterBounds(), sceneBounds, tileSize_);
      if (!m) {
        if (noted_.insert(i).second)
          notes_.push_back(
              "lights[" + std::to_string(i) +
              "]: point light inside or beside the shadow-casting obstacles' bounds: no shadow map "
              "while it is there (no cube maps)");
        continue;
      }
      tileOf_[i] = int(tile);
      lightMatrices_[i] = tileMatrices[tile] = *m;
    }
  }
  matrices_.upload(tileMatrices);
}

void ShadowMaps::record(gpu::Sequence& sequence, const ObstacleMeshes& meshes) const {
  std::vector<gpu::Draw> draws;
  if (meshes.casterIndexCount() > 0)
    for (uint32_t tile = 0; tile < tiles_; ++tile) {
      gpu::Draw draw{pipeline_.get(),      {gpu::reads(matrices_), gpu::reads(meshes.placements())},
                     gpu::pushBytes(tile), &meshes.vertices(),
                     &meshes.indices(),    meshes.casterIndexCount()};
      draw.area = VkRect2D{{0, int32_t(tile * tileSize_)}, {tileSize_, tileSize_}};
      draws.push_back(std::move(draw));
    }
  sequence.beginStage("shadow maps");
  sequence.render({{}, &atlas_, std::nullopt, 1.0f}, draws);
  sequence.endStage();
}

int ShadowMaps::tileOf(size_t light) const {
  return light < tileOf_.size() ? tileOf_[light] : -1;
}

glm::mat4 ShadowMaps::lightViewProjection(size_t light) const {
  return light < lightMatrices_.size() ? lightMatrices_[light] : drawsNothing();
}

std::vector<std::string> ShadowMaps::takeNotes() {
  return std::exchange(notes_, {});
}

}  // namespace sixway::render
