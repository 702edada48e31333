#include "reference/bake_flipbook.h"

#include <chrono>
#include <cstdio>

#include "io/error.h"
#include "io/exr.h"
#include "reference/flipbook.h"
#include "render/billboard.h"
#include "render/sixway.h"

namespace sixway::reference {
namespace {

nlohmann::json vec(glm::vec3 v) {
  return {v.x, v.y, v.z};
}

// `settings`: the ones baked with; `cellOpticalDepth`: what chose their light-grid spacing (with
// job.lightSpacingFromSmoke).
nlohmann::json describe(const FlipbookBake& job, const BakeSettings& settings, float cellOpticalDepth,
                        const render::ImagePlane& billboard, const nlohmann::json& frames) {
  nlohmann::json scattering = {{"mode", scatteringName(job.scattering)}};
  if (job.scattering == Scattering::Multiple) {
    const MultipleScattering& m = job.multiple;
    scattering["method"] = m.traceAllOrders
                               ? "every order path-traced at full resolution"
                               : "exact single scattering + orders >= 2 path-traced at 1/downsample";
    scattering["orders"] = m.maxOrders;
    scattering["samples_per_pixel"] = m.samples;
    if (!m.traceAllOrders) scattering["downsample"] = m.downsample;
    scattering["seed"] = m.seed;
  }
  nlohmann::json p = job.provenance;
  p["camera"] = {{"position", vec(job.camera.position)},
                 {"right", vec(job.camera.right)},
                 {"up", vec(job.camera.up)},
                 {"forward", vec(job.camera.forward)}};
  p["billboard"] = {{"image_plane_min", {billboard.min.x, billboard.min.y}},
                    {"image_plane_max", {billboard.max.x, billboard.max.y}}};
  p["optics"] = {{"extinction", job.smoke.extinction},
                 {"albedo", job.smoke.albedo},
                 {"phase_g", job.smoke.phaseG},
                 {"emission_intensity", job.smoke.emission.intensity}};
  if (job.smoke.emission.intensity > 0) {
    nlohmann::json ramp = nlohmann::json::array();  // [temperature, r, g, b], linear, interpolated linearly
    for (const auto& key : job.smoke.emission.ramp)
      ramp.push_back({key.temperature, key.color.r, key.color.g, key.color.b});
    p["optics"]["emission_ramp"] = ramp;
  }
  p["bake"] = {{"step_cells", settings.stepCells},
               {"light_grid_spacing_cells", settings.lightSpacingCells},
               {"scattering", scattering}};
  if (job.lightSpacingFromSmoke)
    p["bake"]["light_grid_spacing_rule"] = {
        {"rule", "0.5 / the densest cell's optical depth, within [0.25, 1]"},
        {"densest_cell_optical_depth", cellOpticalDepth}};
  p["frames"] = frames;
  return p;
}

}  // namespace

FlipbookBakeResult bakeFlipbook(const gpu::Context& context, const gpu::PipelineCache& cache,
                                render::VolumeSequence& sequence, const FlipbookBake& job,
                                const std::function<void(const std::string&)>& progress) {
  const int available = sequence.frameCount();
  if (job.frameCount < 1 || job.firstFrame < 0 || job.firstFrame + job.frameCount > available)
    throw io::InputError("frames", std::to_string(job.firstFrame) + ".." +
                                       std::to_string(job.firstFrame + job.frameCount - 1) +
                                       " are outside the sequence, which has frames 0.." +
                                       std::to_string(available - 1));
  const int width = job.settings.width, height = job.settings.height;
  const FlipbookLayout layout = flipbookLayout(job.frameCount, width, height, job.columns);
  requireFlipbookFits(layout, "flipbook");
  FlipbookBakeResult result;
  result.billboard = render::billboardBounds(job.camera, sequence.bounds(), float(width) / float(height));

  ScatteredLightmaps baker(context, cache);
  // One spacing for the whole flipbook, so that the light grids neither move nor grow from frame to frame.
  BakeSettings settings = job.settings;
  float cellOpticalDepth = 0;
  if (job.lightSpacingFromSmoke) {
    cellOpticalDepth =
        job.smoke.extinction * sequence.densityBound(job.firstFrame, job.frameCount) * sequence.cellSize();
    settings.lightSpacingCells = lightSpacingFor(cellOpticalDepth);
  }
  std::filesystem::create_directories(job.out / "frames");

  const auto& names = render::sixWayChannelNames();
  std::vector<io::Image> tiles;
  nlohmann::json frames = nlohmann::json::array();
  for (int i = 0; i < job.frameCount; ++i) {
    const int index = job.firstFrame + i;
    const auto start = std::chrono::steady_clock::now();
    const std::optional<render::Volume> volume = sequence.frame(index);
    io::Image tile(width, height, {names.begin(), names.end()});
    double gpuMs = 0;
    if (volume) {
      tile = baker.bake(*volume, job.smoke, job.camera, result.billboard, settings, job.scattering,
                        job.multiple);
      gpuMs = baker.milliseconds();
    }
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%04d.exr", index);
    io::writeExr(job.out / "frames" / name, tile, io::ExrPixelType::Float,
                 {{"colorspace", "linear"}, {"sixway", "six-way lightmaps, premultiplied"}});
    tiles.push_back(std::move(tile));
    result.frameMilliseconds.push_back(gpuMs);
    frames.push_back({{"index", index},
                      {"name", sequence.frameName(index)},
                      {"empty", !volume},
                      {"file", std::string("frames/") + name}});
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    char line[256];
    std::snprintf(line, sizeof(line), "frame %d/%d (%s): %s, %.1f ms GPU, %.2f s", i + 1, job.frameCount,
                  sequence.frameName(index).c_str(), volume ? "baked" : "empty", gpuMs, seconds);
    progress(line);
  }
  result.layout = layout;
  if (job.emissiveMask) result.emissiveMask = unityEmissiveMask(job.smoke);
  result.sidecar = writeFlipbook(job.out, "flipbook", tiles, layout, job.packing,
                                 describe(job, settings, cellOpticalDepth, result.billboard, frames),
                                 job.scattering, result.emissiveMask);
  return result;
}

}  // namespace sixway::reference
