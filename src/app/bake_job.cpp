#include "app/bake_job.h"

#include <regex>
#include <stdexcept>
#include <string>
#include <utility>

#include "app/device_limits.h"
#include "gpu/context.h"
#include "io/error.h"
#include "modes/scene_source.h"
#include "reference/flipbook.h"
#include "reference/vdb_sequence.h"
#include "render/scene_frame.h"

namespace sixway::app {
namespace {

namespace fs = std::filesystem;

// "128" or "128x256".
std::pair<int, int> parseTile(const std::string& text) {
  std::smatch m;
  if (!std::regex_match(text, m, std::regex(R"((\d{1,5})(?:x(\d{1,5}))?)")))
    throw io::InputError("--tile", "expected N or WxH (got \"" + text + "\")");
  const int w = std::stoi(m[1]), h = m[2].matched ? std::stoi(m[2]) : w;
  if (w < 1 || h < 1 || w > 8192 || h > 8192) throw io::InputError("--tile", "each side must be in 1..8192");
  return {w, h};
}

glm::vec3 vec3Of(const std::vector<float>& v) {
  return {v[0], v[1], v[2]};
}

// The fixed view: --camera-* flags, else the scene's camera (at frame 0), else the default framing camera.
render::Camera chooseCamera(const BakeOptions& o, const scene::Scene* scene, const render::Box& bounds) {
  const float fov = o.fov.value_or(scene ? scene->camera.fovDeg : 40.0f);
  if (!o.cameraPosition.empty()) {
    const glm::vec3 up = o.cameraUp.empty() ? glm::vec3(0, 1, 0) : vec3Of(o.cameraUp);
    try {
      return render::Camera::lookAt(vec3Of(o.cameraPosition), vec3Of(o.cameraTarget), up, fov);
    } catch (const std::invalid_argument& e) {
      throw io::InputError("--camera-position", std::string(e.what()).substr(std::string("camera: ").size()));
    }
  }
  if (scene) {
    scene::Camera camera = scene->camera;
    camera.fovDeg = fov;
    return render::sceneCamera(camera, 0);
  }
  return render::framingCamera(bounds, fov);
}

// The five-key emission ramp used for OpenVDB files with --emission (temperature 0 … 1, black to white-hot).
scene::Emission defaultRamp(float intensity) {
  scene::Emission e;
  e.intensity = intensity;
  e.ramp = {{0.0f, {0.0f, 0.0f, 0.0f}},
            {0.25f, {0.5f, 0.05f, 0.0f}},
            {0.5f, {1.0f, 0.35f, 0.05f}},
            {0.75f, {1.0f, 0.7f, 0.3f}},
            {1.0f, {1.0f, 0.95f, 0.8f}}};
  return e;
}

BakeSource openScene(const gpu::Context& context, const gpu::PipelineCache& cache, const BakeOptions& o,
                     scene::Scene& scene, int frameCount) {
  BakeSource source;
  source.sequence = withinDeviceLimits(
      o.scene.string(), scene.vdb ? "vdb.voxels" : gridSetting(scene.grid),
      [&] { return modes::openSceneVolumes(context, cache, scene, o.first + frameCount, o.scene.string()); });
  source.provenance["source"] = {{"scene", fs::absolute(o.scene).string()}};
  if (scene.vdb) source.provenance["source"].update(modes::describeSource(*source.sequence));
  return source;
}

BakeSource openVdbFiles(const gpu::Context& context, const BakeOptions& o, const scene::Smoke& smoke) {
  const int voxels = o.voxels.value_or(128);
  const std::string given = voxels == scene::kNativeVoxels ? "native" : std::to_string(voxels);
  auto vdb = withinDeviceLimits("--voxels " + given, "--voxels", [&] {
    return std::make_unique<reference::VdbSequence>(context, o.vdb, voxels, smoke.emission.intensity > 0.0f,
                                                    o.densityGrid.value_or("density"));
  });
  nlohmann::json files = nlohmann::json::array();
  for (const fs::path& f : o.vdb) files.push_back(fs::absolute(f).string());
  const render::VolumeGrid& lattice = vdb->lattice();
  BakeSource source;
  source.provenance["source"] = {{"vdb", files},
                                 {"density_grid", vdb->source().densityGrid},
                                 {"lattice",
                                  {{"cells", {lattice.size.x, lattice.size.y, lattice.size.z}},
                                   {"origin", {lattice.origin.x, lattice.origin.y, lattice.origin.z}},
                                   {"cell_size", lattice.cellSize}}}};
  if (vdb->source().temperatureGrid)
    source.provenance["source"]["temperature_grid"] = *vdb->source().temperatureGrid;
  source.sequence = std::move(vdb);
  return source;
}

// Single scattering, or multiple with its settings; the multiple-scattering options refused with single.
void setScattering(reference::FlipbookBake& job, const BakeOptions& o, const scene::Scene* scene) {
  job.scattering = reference::parseScattering(o.scattering, "--scattering");
  if (job.scattering == reference::Scattering::Single &&
      (o.samples || o.orders || o.downsample || o.seed || o.traceAllOrders))
    throw io::InputError("--scattering single",
                         "--spp, --orders, --ms-downsample, --ms-all-orders and --seed "
                         "are for multiple scattering");
  if (o.traceAllOrders && o.downsample)
    throw io::InputError("--ms-all-orders", "traces at full resolution: no --ms-downsample");
  if (o.samples) job.multiple.samples = uint32_t(*o.samples);
  if (o.orders) job.multiple.maxOrders = *o.orders;
  if (o.downsample) job.multiple.downsample = *o.downsample;
  job.multiple.traceAllOrders = o.traceAllOrders;
  job.multiple.seed = o.seed.value_or(scene ? scene->render.seed : 1u);
}

}  // namespace

std::optional<scene::Scene> bakedScene(const BakeOptions& o) {
  std::optional<scene::Scene> scene;
  if (!o.scene.empty()) scene = scene::loadScene(o.scene);
  if (scene && o.voxels) {
    if (!scene->vdb)
      throw io::InputError("--voxels", "only for VDB input (--vdb, or a scene with a vdb section)");
    scene->vdb->voxels = *o.voxels;
  }
  return scene;
}

scene::Smoke bakedSmoke(const BakeOptions& o, const scene::Scene* scene) {
  scene::Smoke smoke = scene ? scene->smoke : scene::Smoke{};
  if (o.extinction) smoke.extinction = *o.extinction;
  if (o.albedo) smoke.albedo = *o.albedo;
  if (o.g) smoke.phaseG = *o.g;
  if (o.emission) {
    if (scene && !smoke.emission.ramp.empty()) {
      smoke.emission.intensity = *o.emission;
    } else {
      smoke.emission = defaultRamp(*o.emission);
    }
  }
  return smoke;
}

BakeTile bakedTile(const BakeOptions& o, const scene::Scene* scene) {
  if (!o.tile.empty()) {
    const auto [width, height] = parseTile(o.tile);
    return {width, height};
  }
  const int size = scene ? scene->render.lightmapSize : 128;
  return {size, size};
}

int bakedFrameCount(const BakeOptions& o, const scene::Scene* scene, BakeTile tile) {
  const int sourceFrames = scene ? scene::sceneFrameCount(*scene) : int(o.vdb.size());
  const int frameCount = o.frames.value_or(scene && !scene->vdb ? 16 : sourceFrames - o.first);
  reference::requireFlipbookFits(
      reference::flipbookLayout(frameCount, tile.width, tile.height, o.columns.value_or(0)),
      "--frames/--tile");
  return frameCount;
}

BakeSource openBakeSource(const gpu::Context& context, const gpu::PipelineCache& cache, const BakeOptions& o,
                          scene::Scene* scene, const scene::Smoke& smoke, int frameCount) {
  return scene ? openScene(context, cache, o, *scene, frameCount) : openVdbFiles(context, o, smoke);
}

reference::FlipbookBake bakeJob(const BakeOptions& o, const scene::Scene* scene, const BakeSource& source,
                                const scene::Smoke& smoke, BakeTile tile, int frameCount) {
  reference::FlipbookBake job;
  job.firstFrame = o.first;
  job.frameCount = frameCount;
  job.columns = o.columns.value_or(0);
  job.packing = reference::packingPreset(o.packing);
  job.emissiveMask = o.emissive == "mask";
  job.camera = chooseCamera(o, scene, source.sequence->bounds());
  job.smoke = smoke;
  job.settings.width = tile.width;
  job.settings.height = tile.height;
  if (o.step) job.settings.stepCells = *o.step;
  if (o.lightSpacing) job.settings.lightSpacingCells = *o.lightSpacing;
  job.lightSpacingFromSmoke = !o.lightSpacing;
  setScattering(job, o, scene);
  job.provenance = source.provenance;
  return job;
}

}  // namespace sixway::app
