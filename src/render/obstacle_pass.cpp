#include "render/obstacle_pass.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <string>
#include <variant>

#include "gpu/image.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "io/error.h"
#include "render/gpu_layout.h"
#include "render/obstacle_meshes.h"
#include "render/shadow_maps.h"
#include "render/volume.h"

namespace sixway::render {
namespace {

constexpr int kMaxLights = 8;  // OBSTACLE_MAX_LIGHTS, shaders/render/obstacle_params.glsl

struct ObstacleParams {  // std140 mirror of shaders/render/obstacle_params.glsl
  glm::mat4 viewProjection;
  glm::vec4 eye;
  glm::vec4 albedo;
  glm::vec4 ambient[4];
  glm::vec4 lightVector[kMaxLights];
  glm::vec4 lightIntensity[kMaxLights];
  glm::vec4 lightShadow[kMaxLights];
  glm::mat4 lightViewProjection[kMaxLights];
};
static_assert(sizeof(ObstacleParams) == 16 * (4 + 1 + 1 + 4 + 3 * kMaxLights + 4 * kMaxLights));

struct ObstaclePush {  // shaders/render/obstacle.frag
  layout::VolumeGrid smoke;
  glm::vec4 optics;
};

// The world distance between neighbouring texel centres of a tile of `tileSize` texels, per unit of clip w
// (w = 1 for a directional light's orthographic projection, the distance along a point light's axis for its
// perspective one), taken at the centre of the tile.
float texelSizePerW(const glm::mat4& lightViewProjection, uint32_t tileSize) {
  const glm::mat4 inverse = glm::inverse(lightViewProjection);
  const glm::vec4 a = inverse * glm::vec4(0.0f, 0.0f, 0.5f, 1.0f);
  const glm::vec4 b = inverse * glm::vec4(2.0f / float(tileSize), 0.0f, 0.5f, 1.0f);
  const glm::vec3 pa = glm::vec3(a) / a.w, pb = glm::vec3(b) / b.w;
  return glm::length(pb - pa) / (lightViewProjection * glm::vec4(pa, 1.0f)).w;
}

}  // namespace

ObstaclePass::ObstaclePass(const gpu::Context& context, const gpu::PipelineCache& cache, glm::vec3 background)
    : background_(background),
      nearest_(std::make_unique<gpu::Sampler>(context, VK_FILTER_NEAREST)),
      params_(context, sizeof(ObstacleParams), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
              gpu::MemoryKind::FrameParameters, "obstacle pass parameters"),
      noSmoke_(gpu::Buffer::storage(context, sizeof(float), "no smoke for the obstacles")) {
  gpu::GraphicsPipelineDesc desc;
  desc.vertexShader = "render/obstacle.vert";
  desc.fragmentShader = "render/obstacle.frag";
  desc.bindings = {gpu::BindingType::UniformBuffer, gpu::BindingType::StorageBuffer,
                   gpu::BindingType::SampledImage, gpu::BindingType::StorageBuffer};
  desc.pushConstantBytes = sizeof(ObstaclePush);
  desc.vertexStride = sizeof(ObstacleVertex);
  desc.attributes = ObstacleMeshes::vertexAttributes();
  desc.colorFormats = {kColorFormat};
  desc.depthFormat = kDepthFormat;
  desc.depthTest = desc.depthWrite = true;
  pipeline_ = std::make_unique<gpu::Pipeline>(context, cache, desc);
}

ObstaclePass::~ObstaclePass() = default;

void ObstaclePass::update(const Camera& camera, const ImagePlane& plane, DepthRange range,
                          std::span<const scene::Light> lights, const std::optional<scene::Ambient>& ambient,
                          const ShadowMaps& shadows) {
  if (lights.size() > size_t(kMaxLights))
    throw io::InputError("lights", std::to_string(lights.size()) +
                                       " lights; the obstacle pass takes at most " +
                                       std::to_string(kMaxLights));
  viewProjection_ = projectionMatrix(plane, range) * viewMatrix(camera);
  ObstacleParams p{};
  p.viewProjection = viewProjection_;
  p.eye = glm::vec4(camera.position, float(shadows.tileSize()));
  p.albedo = glm::vec4(kObstacleAlbedo, float(lights.size()));
  if (ambient) {
    if (const auto* constant = std::get_if<scene::AmbientColor>(&*ambient))
      p.ambient[0] = glm::vec4(constant->color, 0.0f);
    else
      for (int i = 0; i < 4; ++i)
        p.ambient[i] = glm::vec4(std::get<scene::AmbientSh>(*ambient).coefficients[i], 0.0f);
  }
  for (size_t i = 0; i < lights.size(); ++i) {
    const scene::Light& light = lights[i];
    if (const auto* directional = std::get_if<scene::DirectionalLight>(&light.source))
      p.lightVector[i] = glm::vec4(directional->direction, 0.0f);
    else
      p.lightVector[i] = glm::vec4(std::get<scene::PointLight>(light.source).position, 1.0f);
    p.lightIntensity[i] = glm::vec4(light.color * light.intensity, 0.0f);
    const int tile = shadows.tileOf(i);
    p.lightViewProjection[i] = shadows.lightViewProjection(i);
    p.lightShadow[i] =
        glm::vec4(float(tile), tile < 0 ? 0.0f : texelSizePerW(p.lightViewProjection[i], shadows.tileSize()),
                  0.0f, 0.0f);
  }
  params_.upload(std::as_bytes(std::span(&p, 1)));
}

void ObstaclePass::record(gpu::Sequence& sequence, const ObstacleMeshes& meshes, const ShadowMaps& shadows,
                          const gpu::Image& color, const gpu::Image& depth, const Volume* smoke,
                          const scene::Smoke& smokeOptics) const {
  ObstaclePush push{};
  if (smoke) {
    requireConsistent(*smoke);
    push.smoke = layout::volumeGrid(smoke->grid);
    push.optics = glm::vec4(smokeOptics.extinction, smokeOptics.albedo, smokeOptics.phaseG, 0.0f);
  }
  std::vector<gpu::Draw> draws;
  if (!meshes.empty())
    draws.push_back(
        {pipeline_.get(),
         {gpu::reads(params_), gpu::reads(meshes.placements()), gpu::samples(shadows.atlas(), *nearest_),
          gpu::reads(smoke ? *smoke->density : noSmoke_)},
         gpu::pushBytes(push),
         &meshes.vertices(),
         &meshes.indices(),
         meshes.indexCount()});
  sequence.beginStage("obstacles");
  sequence.render(
      {{&color}, &depth, std::array<float, 4>{background_.r, background_.g, background_.b, 0.0f}, 1.0f},
      draws);
  sequence.endStage();
}

}  // namespace sixway::render
