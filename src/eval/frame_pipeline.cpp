#include "eval/frame_pipeline.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

#include "gpu/context.h"
#include "gpu/image.h"
#include "gpu/pipeline.h"
#include "io/error.h"
#include "nn/network.h"
#include "reference/guide_lightmaps.h"
#include "reference/path_tracer.h"
#include "reference/scattered_lightmaps.h"
#include "render/billboard.h"
#include "render/camera.h"
#include "render/guiding_map.h"
#include "render/lightmap_images.h"
#include "render/obstacle_bvh.h"
#include "render/obstacle_meshes.h"
#include "render/obstacle_pass.h"
#include "render/projection.h"
#include "render/recorded_sequence.h"
#include "render/scene_frame.h"
#include "render/shadow_maps.h"
#include "render/sixway_shading.h"
#include "runtime/network_weights.h"
#include "runtime/realtime_frame.h"

namespace sixway::eval {
namespace {

// An RGBA16F image on the host, as floats named `channels`.
io::Image downloadHalfImage(const gpu::Image& image, std::vector<std::string> channels) {
  io::Image out(int(image.desc().width), int(image.desc().height), std::move(channels));
  const std::vector<uint16_t> texels = image.download<uint16_t>();
  for (size_t i = 0; i < out.pixels.size(); ++i) out.pixels[i] = glm::unpackHalf1x16(texels[i]);
  return out;
}

// The traditional billboard: the rectangle baked from `baked` (at the volume centre's depth there) kept at
// the same world size and offset, facing `camera` — a camera-facing sprite, as engines draw flipbooks.
render::ImagePlane facingBillboard(const render::Camera& camera, const render::Camera& baked,
                                   const render::ImagePlane& bakedPlane, glm::vec3 centre) {
  const auto project = [&](const render::Camera& c) {
    const glm::vec3 v = centre - c.position;
    const float z = glm::dot(v, c.forward);
    return std::pair(glm::vec2(glm::dot(v, c.right), glm::dot(v, c.up)) / z, z);
  };
  const auto [bakedCentre, bakedDepth] = project(baked);
  const auto [centreNow, depthNow] = project(camera);
  const float scale = bakedDepth / depthNow;
  return {centreNow + (bakedPlane.min - bakedCentre) * scale,
          centreNow + (bakedPlane.max - bakedCentre) * scale};
}

// The scene the real-time passes draw: the path tracer draws the obstacles itself (opaque surfaces in the
// truth), so its rasterized frame is the background alone.
io::Scene rasterScene(const io::Scene& scene, RenderMode mode) {
  io::Scene raster = scene;
  if (mode == RenderMode::PathTrace) raster.obstacles.clear();
  return raster;
}

bool isTraditional(RenderMode mode) {
  return mode == RenderMode::Traditional || mode == RenderMode::TraditionalMs;
}

// The modes whose lightmaps the reference baker computes, and with which scattering.
std::optional<render::Scattering> bakedScattering(RenderMode mode) {
  if (mode == RenderMode::Reference || mode == RenderMode::Traditional) return render::Scattering::Single;
  if (mode == RenderMode::ReferenceMs || mode == RenderMode::TraditionalMs)
    return render::Scattering::Multiple;
  return std::nullopt;
}

}  // namespace

RenderMode parseRenderMode(const std::string& name) {
  for (RenderMode m :
       {RenderMode::Neural, RenderMode::Reference, RenderMode::ReferenceMs, RenderMode::Traditional,
        RenderMode::TraditionalMs, RenderMode::Guide, RenderMode::GuideLit, RenderMode::PathTrace})
    if (name == renderModeName(m)) return m;
  throw io::InputError("--mode",
                       "unknown mode \"" + name +
                           "\" (known: neural, reference, reference-ms, traditional, traditional-ms, "
                           "guide, guide-lit, pathtrace)");
}

const char* renderModeName(RenderMode mode) {
  switch (mode) {
    case RenderMode::Neural:
      return "neural";
    case RenderMode::Reference:
      return "reference";
    case RenderMode::ReferenceMs:
      return "reference-ms";
    case RenderMode::Traditional:
      return "traditional";
    case RenderMode::TraditionalMs:
      return "traditional-ms";
    case RenderMode::Guide:
      return "guide";
    case RenderMode::GuideLit:
      return "guide-lit";
    case RenderMode::PathTrace:
      return "pathtrace";
  }
  return "?";
}

struct FramePipeline::Passes {
  Passes(const gpu::Context& context, const gpu::PipelineCache& cache, const io::Scene& scene,
         const FramePipelineOptions& options)
      : context(context),
        scene(scene),
        raster(rasterScene(scene, options.mode)),
        options(options),
        network(options.mode == RenderMode::Neural
                    ? runtime::loadNetwork(context, cache, options.weights,
                                           uint32_t(scene.render.lightmapSize),
                                           runtime::sceneNetworkOptions(scene, options.fp16))
                    : nullptr),
        frame(context, cache, raster,
              runtime::FrameTarget{uint32_t(scene.render.width), uint32_t(scene.render.height), {}, {}},
              !options.shadows      ? 0
              : options.shadowTiles ? *options.shadowTiles
                                    : render::shadowTileCount(raster.lights, raster.obstacles),
              network ? runtime::networkGuide(scene, network->graph())
                      : render::GuideSettings::fromScene(scene)),
        sequence(context) {
    if (bakedScattering(options.mode)) baker = std::make_unique<render::ScatteredLightmaps>(context, cache);
    if (options.mode == RenderMode::PathTrace) {
      tracer = std::make_unique<render::PathTracer>(context, cache);
      if (!scene.obstacles.empty())
        obstacles = std::make_unique<render::ObstacleBvh>(context, scene.obstacles);
    }
    if (options.mode == RenderMode::GuideLit)
      guideLit = std::make_unique<render::GuideLightmaps>(context, cache,
                                                          uint32_t(frame.guiding().settings().lights.size()));
  }

  // The real-time stages of the mode, recorded once for the volume's buffers.
  gpu::Sequence& realtimeSequence(const render::Volume& volume) {
    return sequence.get({render::handleKey(volume.density->handle())}, [&](gpu::Sequence& s) {
      // A flipbook has no guide: its shell depth is uploaded per frame instead.
      const runtime::FrameStages stages =
          options.mode == RenderMode::PathTrace ? runtime::FrameStages::ObstaclesOnly
          : options.mode == RenderMode::Guide   ? runtime::FrameStages::UpToGuide
          : isTraditional(options.mode)         ? runtime::FrameStages::AllButGuide
                                                : runtime::FrameStages::All;
      frame.record(s, volume, stages, [&](gpu::Sequence& s) {
        if (network) {
          s.beginStage("network");
          network->record(s, {frame.guide(), frame.guideEmission()}, frame.lightmaps().a,
                          frame.lightmaps().b);
          s.endStage();
        }
        if (guideLit) guideLit->record(s, frame.guide(), frame.lightmaps());
      });
    });
  }

  const gpu::Context& context;
  io::Scene scene;
  io::Scene raster;  // what the real-time passes draw (rasterScene)
  FramePipelineOptions options;
  std::unique_ptr<nn::Network> network;  // before the frame, whose guide it sets
  runtime::RealtimeFrame frame;
  std::unique_ptr<render::ScatteredLightmaps> baker;
  std::unique_ptr<render::PathTracer> tracer;
  std::unique_ptr<render::ObstacleBvh> obstacles;  // pathtrace, with obstacles
  std::unique_ptr<render::GuideLightmaps> guideLit;
  render::RecordedSequence sequence;
  std::optional<std::pair<render::Camera, render::ImagePlane>> bakedView;  // traditional: the first frame's
};

FramePipeline::FramePipeline(const gpu::Context& context, const gpu::PipelineCache& cache,
                             const io::Scene& scene, const FramePipelineOptions& options)
    : passes_(std::make_unique<Passes>(context, cache, scene, options)) {}

FramePipeline::~FramePipeline() = default;

FrameView sceneView(const io::Scene& scene, int index) {
  return {render::sceneCamera(scene.camera, index), render::sceneLights(scene.lights, index)};
}

RenderedFrame FramePipeline::render(int index, double seconds, const render::Volume& volume) {
  return render(sceneView(passes_->scene, index), index, seconds, volume);
}

RenderedFrame FramePipeline::render(const FrameView& view, int index, double seconds,
                                    const render::Volume& volume) {
  Passes& p = *passes_;
  const io::Scene& scene = p.scene;
  const render::Camera& camera = view.camera;
  const std::vector<io::Light>& lights = view.lights;
  const render::Box volumeBox = volume.grid.bounds();

  // Recording allocates what the passes need for this volume, so it comes before their per-frame values.
  gpu::Sequence& sequence = p.realtimeSequence(volume);
  p.frame.updateScene(camera, lights, seconds);
  RenderedFrame result;
  result.notes = p.frame.takeNotes();

  const bool traditional = isTraditional(p.options.mode);
  const bool guided = !traditional && p.options.mode != RenderMode::PathTrace;
  render::ImagePlane billboard = guided ? p.frame.updateGuide(camera, volumeBox, index)
                                        : render::billboardBounds(camera, volumeBox, 1.0f);
  const uint32_t lightmapSize = p.frame.lightmapSize();
  if (const std::optional<render::Scattering> scattering = bakedScattering(p.options.mode)) {
    // Reference: baked for this frame's view. Traditional: for the first frame's, as a flipbook is.
    if (traditional && !p.bakedView) p.bakedView.emplace(camera, billboard);
    const render::Camera& bakeCamera = traditional ? p.bakedView->first : camera;
    const render::ImagePlane& bakePlane = traditional ? p.bakedView->second : billboard;
    render::BakeSettings bake;
    bake.width = bake.height = int(lightmapSize);
    render::MultipleScattering multiple = p.options.multipleScattering;
    multiple.seed = scene.render.seed + uint32_t(index);  // independent noise frame to frame
    p.frame.lightmaps().upload(
        p.baker->bake(volume, scene.smoke, bakeCamera, bakePlane, bake, *scattering, multiple));
    for (const gpu::StageTime& t : p.baker->stageTimes())
      result.stages.push_back({"bake/" + t.name, t.milliseconds});
  }
  if (traditional) {
    billboard = facingBillboard(camera, p.bakedView->first, p.bakedView->second, volumeBox.centre());
    // A flipbook knows no depth but its quad's: the shell is the billboard plane through the volume centre.
    const render::DepthRange shellRange = render::boxDepthRange(camera, volumeBox);
    const float planeDepth = glm::dot(volumeBox.centre() - camera.position, camera.forward);
    const float encoded = (planeDepth - shellRange.near) / (shellRange.far - shellRange.near);
    // Against obstacles the card fades over the volume's depth, as soft particles do: an opacity of 1
    // building up evenly over the box's depth range (the guide's alpha 1, the opacity levels at their share
    // of the range).
    std::vector<uint16_t> flat(size_t(lightmapSize) * lightmapSize * 4, 0);
    for (size_t i = 0; i < flat.size(); i += 4) {
      flat[i + 1] = glm::packHalf1x16(1.0f);
      flat[i + 2] = glm::packHalf1x16(glm::clamp(encoded, 0.0f, 1.0f));
    }
    p.frame.guide().upload(std::as_bytes(std::span(flat)));
    constexpr float kLevels[4] = {0.1f, 0.35f, 0.6f, 0.85f};  // shaders/common/depth.glsl, kOpacityLevels
    std::vector<uint16_t> levels(size_t(lightmapSize) * lightmapSize * 4);
    for (size_t i = 0; i < levels.size(); ++i) levels[i] = glm::packHalf1x16(kLevels[i % 4]);
    p.frame.guiding().opacityDepths().upload(std::as_bytes(std::span(levels)));
  }
  p.frame.updateShading(camera, lights, billboard, volumeBox);

  sequence.submit();
  result.stages.insert(result.stages.end(), sequence.stageTimes().begin(), sequence.stageTimes().end());

  if (!p.options.download) return result;
  if (p.options.mode == RenderMode::Guide) {
    result.image = guide();
    return result;
  }
  result.image = downloadHalfImage(p.frame.color(), {"R", "G", "B", "A"});
  if (p.options.mode != RenderMode::PathTrace) return result;

  // Ground truth: the path-traced smoke and obstacles (black background, so premultiplied; opaque obstacles)
  // over the rasterized background.
  render::TraceSettings trace;
  trace.width = int(p.frame.width());
  trace.height = int(p.frame.height());
  trace.seed = scene.render.seed + uint32_t(index) + p.options.pathTraceSeedOffset;
  trace.maxOrders = p.options.pathTraceOrders;
  if (scene.ambient) {
    if (const auto* c = std::get_if<io::AmbientColor>(&*scene.ambient)) trace.environment = {c->color};
    if (const auto* sh = std::get_if<io::AmbientSh>(&*scene.ambient)) trace.environment = sh->coefficients;
  }
  std::vector<io::Light> traced = lights;
  if (!p.options.shadows)
    for (io::Light& light : traced) light.shadows = false;
  if (p.obstacles) p.obstacles->update(seconds);
  p.tracer->beginImage(volume, scene.smoke, camera, render::fullFrame(camera, trace.width, trace.height),
                       traced, trace, p.obstacles.get());
  p.tracer->accumulate(p.options.pathTraceSamples);
  result.stages.push_back({"path trace", p.tracer->traceMilliseconds()});
  const io::Image smoke = p.tracer->image();
  for (size_t i = 0, n = size_t(smoke.width) * smoke.height; i < n; ++i) {
    const float alpha = smoke.pixels[i * 4 + 3];
    for (int c = 0; c < 4; ++c)
      result.image.pixels[i * 4 + c] =
          smoke.pixels[i * 4 + c] + (1.0f - alpha) * result.image.pixels[i * 4 + c];
  }
  return result;
}

io::Image FramePipeline::guide() const {
  const io::Image g = downloadHalfImage(passes_->frame.guide(), {"guide", "alpha", "depth", "unused"});
  io::Image out(g.width, g.height, {"guide", "alpha", "depth"});
  for (size_t i = 0, n = size_t(g.width) * g.height; i < n; ++i)
    for (int c = 0; c < 3; ++c) out.pixels[i * 3 + c] = g.pixels[i * 4 + c];
  return out;
}

io::Image FramePipeline::opacityDepths() const {
  return downloadHalfImage(passes_->frame.guiding().opacityDepths(), {"0.1", "0.35", "0.6", "0.85"});
}

io::Image FramePipeline::lightmaps() const {
  return passes_->frame.lightmaps().download();
}

void FramePipeline::setObstacleMotion(size_t obstacle, std::optional<io::Motion> motion) {
  if (passes_->obstacles) passes_->obstacles->setMotion(obstacle, motion);
  if (passes_->options.mode != RenderMode::PathTrace)
    passes_->frame.meshes().setMotion(obstacle, std::move(motion));
}

const gpu::Image& FramePipeline::colorImage() const {
  return passes_->frame.color();
}
const gpu::Image& FramePipeline::guideImage() const {
  return passes_->frame.guide();
}
const gpu::Image& FramePipeline::lightmapImageA() const {
  return passes_->frame.lightmaps().a;
}
const gpu::Image& FramePipeline::lightmapImageB() const {
  return passes_->frame.lightmaps().b;
}

}  // namespace sixway::eval
