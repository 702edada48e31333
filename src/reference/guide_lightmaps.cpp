#include "reference/guide_lightmaps.h"

#include <stdexcept>

#include "gpu/image.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "render/lightmap_images.h"
#include "render/render_spec.h"

namespace sixway::reference {

constexpr uint32_t kGroup = 8;  // the shader's local size in x and y

GuideLightmaps::GuideLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache,
                               uint32_t guideLights) {
  if (guideLights == 0) throw std::invalid_argument("guide lightmaps: no guide lights");
  using gpu::BindingType;
  gpu::ComputePipelineDesc desc{
      "render/guide_lightmaps.comp",
      {BindingType::StorageImage, BindingType::StorageImage, BindingType::StorageImage}};
  desc.spec.set(render::spec::kGuideLights, int32_t(guideLights));
  pass_ = std::make_unique<gpu::Pipeline>(context, cache, desc);
}

GuideLightmaps::~GuideLightmaps() = default;

void GuideLightmaps::record(gpu::Sequence& sequence, const gpu::Image& guide,
                            const render::LightmapImages& lightmaps) const {
  const gpu::ImageDesc& g = guide.desc();
  const gpu::ImageDesc& l = lightmaps.a.desc();
  if (g.width != l.width || g.height != l.height)
    throw std::invalid_argument("guide lightmaps: the guide and the lightmaps differ in size");
  sequence.beginStage("guide lightmaps");
  sequence.dispatch(*pass_, {gpu::reads(guide), gpu::writes(lightmaps.a), gpu::writes(lightmaps.b)},
                    std::span<const std::byte>(), (g.width + kGroup - 1) / kGroup,
                    (g.height + kGroup - 1) / kGroup);
  sequence.endStage();
}

}  // namespace sixway::reference
