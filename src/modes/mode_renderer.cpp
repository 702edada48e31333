#include "modes/mode_renderer.h"

#include <glm/gtc/packing.hpp>

#include "gpu/image.h"
#include "modes/baked_lightmaps.h"
#include "modes/fitted_lightmap_source.h"
#include "modes/flipbook_lightmaps.h"
#include "modes/guide_lit_lightmaps.h"
#include "render/shadow_maps.h"
#include "runtime/network_lightmaps.h"
#include "runtime/network_weights.h"

namespace sixway::modes {
namespace {

// An RGBA16F image on the host, as floats named `channels`.
io::Image downloadHalfImage(const gpu::Image& image, std::vector<std::string> channels) {
  io::Image out(int(image.desc().width), int(image.desc().height), std::move(channels));
  const std::vector<uint16_t> texels = image.download<uint16_t>();
  for (size_t i = 0; i < out.pixels.size(); ++i) out.pixels[i] = glm::unpackHalf1x16(texels[i]);
  return out;
}

// The scene the real-time passes draw: the path tracer draws the obstacles itself (opaque surfaces in the
// truth), so its rasterized frame is the background alone.
scene::Scene rasterScene(const scene::Scene& scene, RenderMode mode) {
  scene::Scene raster = scene;
  if (mode == RenderMode::PathTrace) raster.obstacles.clear();
  return raster;
}

std::unique_ptr<runtime::LightmapSource> modeSource(const gpu::Context& context,
                                                    const gpu::PipelineCache& cache,
                                                    const scene::Scene& scene, const ModeOptions& o) {
  const reference::MultipleScattering& multiple = o.multipleScattering;
  switch (o.mode) {
    case RenderMode::Neural:
      return std::make_unique<runtime::NetworkLightmaps>(context, cache, scene,
                                                         runtime::readWeights(o.weights), o.fp16);
    case RenderMode::Reference:
      return std::make_unique<BakedLightmaps>(context, cache, scene, reference::Scattering::Single, multiple);
    case RenderMode::ReferenceMs:
      return std::make_unique<BakedLightmaps>(context, cache, scene, reference::Scattering::Multiple,
                                              multiple);
    case RenderMode::ReferenceFit:
      return std::make_unique<FittedLightmapSource>(context, cache, scene, multiple, o.fitDirections);
    case RenderMode::Traditional:
      return std::make_unique<FlipbookLightmaps>(context, cache, scene, reference::Scattering::Single,
                                                 multiple);
    case RenderMode::TraditionalMs:
      return std::make_unique<FlipbookLightmaps>(context, cache, scene, reference::Scattering::Multiple,
                                                 multiple);
    case RenderMode::Guide:
      return std::make_unique<runtime::LightmapSource>(runtime::FrameStages::UpToGuide);
    case RenderMode::GuideLit:
      return std::make_unique<GuideLitLightmaps>(context, cache, scene);
    case RenderMode::PathTrace:
      return std::make_unique<runtime::LightmapSource>(runtime::FrameStages::ObstaclesOnly);
  }
  return nullptr;
}

uint32_t shadowTiles(const scene::Scene& raster, const ModeOptions& options) {
  if (!options.shadows) return 0;
  return options.shadowTiles ? *options.shadowTiles
                             : render::shadowTileCount(raster.lights, raster.obstacles);
}

}  // namespace

ModeRenderer::ModeRenderer(const gpu::Context& context, const gpu::PipelineCache& cache,
                           const scene::Scene& scene, const ModeOptions& options)
    : scene_(scene),
      raster_(rasterScene(scene, options.mode)),
      options_(options),
      frame_(context, cache, raster_,
             runtime::OwnTarget{uint32_t(scene.render.width), uint32_t(scene.render.height)},
             shadowTiles(raster_, options), modeSource(context, cache, raster_, options)) {
  if (options.mode == RenderMode::PathTrace)
    pathTraced_ = std::make_unique<PathTracedSmoke>(context, cache, scene_, options_);
}

RenderedFrame ModeRenderer::render(int index, double seconds, const render::Volume& volume) {
  return render(runtime::sceneView(scene_, index), index, seconds, volume);
}

RenderedFrame ModeRenderer::render(const runtime::FrameView& view, int index, double seconds,
                                   const render::Volume& volume) {
  gpu::Sequence& sequence = frame_.prepare({volume, 0, view, index, seconds, std::nullopt});
  RenderedFrame result{{}, frame_.source().stageTimes(), frame_.notes()};
  sequence.submit();
  result.stages.insert(result.stages.end(), sequence.stageTimes().begin(), sequence.stageTimes().end());
  if (!options_.download) return result;
  if (options_.mode == RenderMode::Guide) {
    result.image = guide();
    return result;
  }
  result.image = downloadHalfImage(colorImage(), {"R", "G", "B", "A"});
  if (pathTraced_) pathTraced_->composite(result.image, view, index, seconds, volume, result.stages);
  return result;
}

void ModeRenderer::setObstacleMotion(size_t obstacle, std::optional<scene::Motion> motion) {
  if (pathTraced_)
    pathTraced_->setObstacleMotion(obstacle, std::move(motion));
  else
    frame_.frame().meshes().setMotion(obstacle, std::move(motion));
}

io::Image ModeRenderer::guide() const {
  const io::Image g = downloadHalfImage(guideImage(), {"guide", "alpha", "depth", "unused"});
  io::Image out(g.width, g.height, {"guide", "alpha", "depth"});
  for (size_t i = 0, n = size_t(g.width) * g.height; i < n; ++i)
    for (int c = 0; c < 3; ++c) out.pixels[i * 3 + c] = g.pixels[i * 4 + c];
  return out;
}

io::Image ModeRenderer::opacityDepths() const {
  return downloadHalfImage(frame_.frame().guiding().opacityDepths(), {"0.1", "0.35", "0.6", "0.85"});
}

io::Image ModeRenderer::lightmaps() const {
  return frame_.frame().lightmaps().download();
}

const gpu::Image& ModeRenderer::colorImage() const {
  return frame_.frame().color();
}

const gpu::Image& ModeRenderer::guideImage() const {
  return frame_.frame().guide();
}

const gpu::Image& ModeRenderer::lightmapImageA() const {
  return frame_.frame().lightmaps().a;
}

const gpu::Image& ModeRenderer::lightmapImageB() const {
  return frame_.frame().lightmaps().b;
}

}  // namespace sixway::modes
