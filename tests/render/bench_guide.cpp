// The numbers of docs/real-time-rendering.md, "Guiding map" (not a test): the guiding map's GPU time and its
// error against the exact baker's Front + Top + Bottom sum, for the default settings and variations of the
// step and of the light-grid spacing. Time: GPU timestamps of the stage "guide", median of 15 replays after a
// warm-up (and at 128², 256² and 512², with and without the fine alpha of channel A). Error: RMS over the
// pixels where the baker's alpha > 0.01 and the largest error, both relative to the baker's peak; one frame
// and the mean of 16 frames (the jitter averaged out). Usage: guide_bench VDB [SCENE]: the density of one VDB
// frame (e.g. of `sixway sim --vdb-out`) on the scene's smoke lattice, seen by its camera with its optics;
// without a scene, on 128 cells along the longest axis of the active voxels, seen from the front-right-above
// with the shipped scenes' optics.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "io/safetensors.h"
#include "io/vdb.h"
#include "reference/lightmap_baker.h"
#include "render/billboard.h"
#include "render/guiding_map.h"
#include "render/sixway.h"
#include "scene/scene.h"

namespace {

using namespace sixway;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Result {
  double ms, oneRms, oneMax, meanRms, meanMax;
};

Result run(const gpu::Context& context, const gpu::PipelineCache& cache,
           const render::GuideSettings& settings, const render::Volume& volume, const scene::Smoke& smoke,
           const render::Camera& camera, const std::vector<float>& exact, const std::vector<float>& alpha) {
  render::GuidingMap map(context, cache, settings);
  gpu::Image image(context, map.imageDesc());
  std::optional<gpu::Image> emission;
  if (settings.emission) emission.emplace(context, map.emissionDesc());
  gpu::Sequence sequence(context);
  map.record(sequence, volume, image, emission ? &*emission : nullptr);
  sequence.finish();
  const render::Box box = volume.grid.bounds();
  std::vector<double> times;
  const size_t pixels = size_t(settings.size) * settings.size;
  std::vector<double> mean(pixels, 0.0), one(pixels);
  constexpr int kFrames = 16;
  for (uint32_t frame = 0; frame < kFrames; ++frame) {
    map.update(camera, render::billboardBounds(camera, box, 1.0f), render::boxDepthRange(camera, box), smoke,
               frame);
    sequence.submit();
    if (frame > 0) times.push_back(sequence.stageTimes().front().milliseconds);  // frame 0: warm-up
    const io::Tensor half{"", io::DType::F16, {int64_t(image.byteSize() / 2)}, image.download<uint8_t>()};
    const std::vector<float> texels = half.toFloat();
    for (size_t i = 0; i < pixels; ++i) {
      if (frame == 0) one[i] = texels[4 * i];
      mean[i] += texels[4 * i] / kFrames;
    }
  }
  Result r{median(times), 0, 0, 0, 0};
  if (exact.empty()) return r;  // timing only
  const double peak = *std::max_element(exact.begin(), exact.end());
  int n = 0;
  for (size_t i = 0; i < pixels; ++i) {
    if (alpha[i] <= 0.01f) continue;
    ++n;
    r.oneRms += std::pow(one[i] - exact[i], 2);
    r.meanRms += std::pow(mean[i] - exact[i], 2);
    r.oneMax = std::max(r.oneMax, std::fabs(one[i] - exact[i]));
    r.meanMax = std::max(r.meanMax, std::fabs(mean[i] - exact[i]));
  }
  r.oneRms = std::sqrt(r.oneRms / n) / peak;
  r.meanRms = std::sqrt(r.meanRms / n) / peak;
  r.oneMax /= peak;
  r.meanMax /= peak;
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: guide_bench VDB [SCENE]\n");
    return 2;
  }
  const std::optional<scene::Scene> scene =
      argc > 2 ? std::optional(scene::loadScene(argv[2])) : std::nullopt;
  gpu::Context context;
  gpu::PipelineCache cache(context);
  std::printf("device: %s (%s)\n", context.properties().deviceName, context.driver().driverInfo);
  const std::string file = argv[1];
  io::DenseRequest request = io::AutoBounds{128};
  if (scene) {
    const scene::Grid& g = scene->grid;
    request = io::ExplicitBounds{g.origin, g.origin + glm::vec3(g.size) * g.cellSize, g.size * g.smokeUpres};
  }
  const io::DenseGrid density = io::readVdbDense(file, "density", request);
  const render::DeviceVolume volume = render::uploadVolume(context, density);
  const render::VolumeGrid& grid = volume.grid();
  std::printf("volume: %s, %dx%dx%d cells of %.4g\n", file.c_str(), grid.size.x, grid.size.y, grid.size.z,
              grid.cellSize);

  scene::Smoke smoke;  // the shipped scenes' optics: extinction 30 per unit density with 1/30 m cells
  smoke.extinction = 1.0f / grid.cellSize;
  smoke.albedo = 0.9f;
  smoke.phaseG = 0.2f;
  const render::Box box = grid.bounds();
  render::Camera camera = render::Camera::lookAt(
      box.centre() + glm::length(box.size()) * glm::vec3(0.5f, 0.25f, 1.3f), box.centre(), {0, 1, 0}, 40.0f);
  if (scene) {
    smoke = scene->smoke;
    camera = render::Camera::lookAt(scene->camera.position, scene->camera.target, scene->camera.up,
                                    scene->camera.fovDeg);
  }

  render::GuideSettings defaults;
  reference::LightmapBaker baker(context, cache);
  reference::BakeSettings bake;
  bake.width = bake.height = int(defaults.size);
  const io::Image lightmaps =
      baker.bake(volume.view(), smoke, camera, render::billboardBounds(camera, box, 1.0f), bake);
  double bakeMs = 0;
  for (const gpu::StageTime& t : baker.stageTimes()) bakeMs += t.milliseconds;
  std::vector<float> exact, front, alpha;
  for (int y = 0; y < lightmaps.height; ++y)
    for (int x = 0; x < lightmaps.width; ++x) {
      exact.push_back(lightmaps.at(x, y, render::Front) + lightmaps.at(x, y, render::Top) +
                      lightmaps.at(x, y, render::Bottom));
      front.push_back(lightmaps.at(x, y, render::Front));
      alpha.push_back(lightmaps.at(x, y, render::Alpha));
    }
  std::printf("exact bake (8 channels, 0.5-cell step, 1-cell light grids): %.1f ms; F+T+B peak %.3f\n",
              bakeMs, *std::max_element(exact.begin(), exact.end()));
  std::printf("%-30s %9s %22s %22s\n", "guide 128x128", "GPU ms", "1 frame: RMS / max",
              "16 frames: RMS / max");

  struct Variant {
    const char* name;
    float step, spacing;
    std::vector<scene::GuideLight> lights;
  };
  const std::vector<scene::GuideLight> ftb = defaults.lights;
  const std::vector<scene::GuideLight> frontOnly = {scene::GuideLight::Front};
  const std::vector<Variant> variants = {{"default (step 3, grids 2)", 3, 2, ftb},
                                         {"step 1.5, grids 2", 1.5f, 2, ftb},
                                         {"step 6, grids 2", 6, 2, ftb},
                                         {"step 0.5, grids 1", 0.5f, 1, ftb},
                                         {"step 3, grids 1", 3, 1, ftb},
                                         {"step 3, grids 1.5", 3, 1.5f, ftb},
                                         {"step 3, grids 3", 3, 3, ftb},
                                         {"step 3, grids 4", 3, 4, ftb},
                                         {"front only, step 3 (vs Front)", 3, 2, frontOnly},
                                         {"front only, step 0.5 (vs Front)", 0.5f, 2, frontOnly}};
  for (const Variant& v : variants) {
    render::GuideSettings s = defaults;
    s.stepCells = v.step;
    s.shadowSpacingCells = v.spacing;
    s.lights = v.lights;
    const bool frontOnly = v.lights.size() == 1;
    const Result r = run(context, cache, s, volume.view(), smoke, camera, frontOnly ? front : exact, alpha);
    std::printf("%-30s %9.2f %10.4f / %-10.4f %10.4f / %-10.4f\n", v.name, r.ms, r.oneRms, r.oneMax,
                r.meanRms, r.meanMax);
  }
  // The fine alpha in channel A (GuideSettings::alphaStepCells) at the sizes the network runs at,
  // and with it the direct emission (GuideSettings::emission), which reads the file's temperature grid (its
  // "heat", or temperature 0 without one) under a two-key ramp.
  const io::VdbFile info = io::readVdbInfo(file);
  const bool hasHeat = std::any_of(info.grids.begin(), info.grids.end(),
                                   [](const io::VdbGridInfo& g) { return g.name == "heat"; });
  const io::DenseGrid heat =
      hasHeat ? io::readVdbDense(
                    file, "heat",
                    io::ExplicitBounds{density.origin, density.origin + glm::vec3(density.size) * density.dx,
                                       density.size})
              : io::DenseGrid{};
  const render::DeviceVolume heated = render::uploadVolume(context, density, hasHeat ? &heat : nullptr);
  scene::Smoke glowing = smoke;
  glowing.emission = {{{0.0f, glm::vec3(0.0f)}, {1.0f, glm::vec3(1.0f, 0.5f, 0.1f)}}, 1.0f};
  std::printf("\n%-30s %9s %9s %9s %17s\n", "default guide, GPU ms", "no A", "A step 1", "A step 0.5",
              "A + emission, 1");
  for (uint32_t size : {128u, 256u, 512u}) {
    double ms[4];
    int k = 0;
    for (float alphaStep : {0.0f, 1.0f, 0.5f}) {
      render::GuideSettings s = defaults;
      s.size = size;
      s.alphaStepCells = alphaStep;
      ms[k++] = run(context, cache, s, volume.view(), smoke, camera, {}, {}).ms;
    }
    render::GuideSettings s = defaults;
    s.size = size;
    s.alphaStepCells = 1.0f;
    s.emission = true;
    ms[k] = run(context, cache, s, heated.view(), glowing, camera, {}, {}).ms;
    std::printf("%-30s %9.2f %9.2f %9.2f %17.2f\n",
                (std::to_string(size) + "x" + std::to_string(size)).c_str(), ms[0], ms[1], ms[2], ms[3]);
  }
  return 0;
}
