#include "app/bake_command.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "app/device_limits.h"
#include "app/options.h"
#include "app/process_memory.h"
#include "app/scene_errors.h"
#include "app/staged_directory.h"
#include "app/stop_on_signal.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "io/error.h"
#include "io/report.h"
#include "modes/scene_source.h"
#include "reference/bake_flipbook.h"
#include "reference/flipbook.h"
#include "reference/vdb_sequence.h"
#include "render/scene_frame.h"
#include "runtime/internal.h"
#include "scene/scene.h"

namespace sixway::app {
namespace {

namespace fs = std::filesystem;

struct BakeOptions {
  CommonOptions common;
  fs::path scene, out, report;
  std::vector<fs::path> vdb;
  bool force = false, traceAllOrders = false;
  std::string scattering = "multiple";
  std::string packing = "unity";
  std::string emissive = "mask";
  int first = 0;
  std::optional<int> frames, columns, voxels, samples, orders, downsample;
  std::optional<uint32_t> seed;
  std::string tile;
  std::vector<float> cameraPosition, cameraTarget, cameraUp;
  std::optional<float> fov, extinction, albedo, g, emission, step, lightSpacing;
};

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

// The folder of the baked frames inside the output directory.
const StagedDirectory::OutputFolders kBakeFolders{"frames"};

// Whether `name` (relative to the output directory) is a file `sixway bake` writes: the sidecar, the textures
// of every packing preset with their Unity .meta files, and the frames. A bake removes those an earlier bake
// left and it did not replace (another packing's textures, frames outside its range).
bool isBakeOutput(const std::string& name) {
  static const std::regex frame(R"(frames/frame_[0-9]{4,}\.exr)");
  static const std::regex texture(R"(flipbook_([A-Za-z0-9]+)\.(exr|png|tga)(\.meta)?)");
  std::smatch match;
  if (name == "flipbook.json" || std::regex_match(name, frame)) return true;
  if (!std::regex_match(name, match, texture)) return false;
  for (const std::string& preset : reference::packingPresetNames())
    if (std::ranges::count(reference::packingPreset(preset).textures, match[1].str()) > 0) return true;
  return false;
}

// Host and device memory after a baked frame, for long-run checks (docs/robustness.md, "Long runs"): the
// resident set grows by the frame the bake holds until it packs the flipbook, and by nothing else. Kept as
// numbers in a vector reserved for the whole bake, so the record itself does not grow the heap.
struct MemoryRow {
  uint64_t deviceBytes = 0, deviceAllocations = 0, hostResidentBytes = 0;
};

nlohmann::json frameRows(const std::vector<MemoryRow>& rows, const reference::FlipbookBakeResult& result,
                         int firstFrame) {
  nlohmann::json frames = nlohmann::json::array();
  for (size_t i = 0; i < rows.size(); ++i)
    frames.push_back({{"frame", firstFrame + int(i)},
                      {"gpu_ms", result.frameMilliseconds[i]},
                      {"device_bytes", rows[i].deviceBytes},
                      {"device_allocations", rows[i].deviceAllocations},
                      {"host_resident_bytes", rows[i].hostResidentBytes}});
  return frames;
}

// "A = (Right, Top, Back, alpha), B = (Left, Bottom, Front, emissive)"
std::string describePacking(const reference::ChannelPacking& packing) {
  std::string text;
  for (int t = 0; t < int(packing.textures.size()); ++t) {
    std::array<std::string, 4> components{"0", "0", "0", "0"};
    for (int c = 0; c < render::kSixWayChannels; ++c)
      if (packing.slots[c].texture == t)
        components[packing.slots[c].component] = render::sixWayChannelNames()[c];
    text += (t ? "), " : "") + packing.textures[t] + " = (" + components[0] + ", " + components[1] + ", " +
            components[2] + ", " + components[3];
  }
  return text + ")";
}

// Unity's emission settings for the flipbook: Single Channel with the sidecar's gradient and multiplier, or
// none.
void printEmissiveSettings(const std::optional<reference::EmissiveMask>& mask, bool maskRequested) {
  if (!mask) {
    std::printf("sixway bake: Unity: Emissive Mode None (%s)\n",
                maskRequested ? "the smoke does not emit" : "--emissive premultiplied: not Unity's mask");
    return;
  }
  std::printf("sixway bake: Unity: Emissive Mode Single Channel, Emissive Multiplier %.6g, Emissive Gradient",
              mask->multiplier);
  for (const render::GradientKey& k : mask->gradient)
    std::printf(" %.4g:(%.4g, %.4g, %.4g)", k.position, k.color.r, k.color.g, k.color.b);
  std::printf(" (position:(linear RGB); also in the sidecar's \"emissive\")\n");
}

void run(const BakeOptions& o) {
  const StopOnSignal stopOnSignal;
  if (o.scene.empty() && o.vdb.empty()) throw io::InputError("bake", "give --scene S or --vdb F...");
  if (o.cameraPosition.empty() != o.cameraTarget.empty())
    throw io::InputError("--camera-position", "--camera-position and --camera-target go together");
  // A directory or special file under a name the bake replaces stops it here, before any work.
  StagedDirectory::requireWritable(o.out, o.force, isBakeOutput, kBakeFolders);
  if (!o.report.empty()) io::requireWritableFile(o.report, o.force);

  std::optional<scene::Scene> scene;
  if (!o.scene.empty()) scene = scene::loadScene(o.scene);
  if (scene && o.voxels) {
    if (!scene->vdb)
      throw io::InputError("--voxels", "only for VDB input (--vdb, or a scene with a vdb section)");
    scene->vdb->voxels = *o.voxels;
  }
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
  const auto [tileWidth, tileHeight] = o.tile.empty() ? std::pair(scene ? scene->render.lightmapSize : 128,
                                                                  scene ? scene->render.lightmapSize : 128)
                                                      : parseTile(o.tile);
  // The flipbook's size is known before anything is simulated or loaded (a scene bakes 16 frames unless
  // told).
  const int sourceFrames = scene ? scene::sceneFrameCount(*scene) : int(o.vdb.size());
  const int frameCount = o.frames.value_or(scene && !scene->vdb ? 16 : sourceFrames - o.first);
  reference::requireFlipbookFits(
      reference::flipbookLayout(frameCount, tileWidth, tileHeight, o.columns.value_or(0)), "--frames/--tile");

  const Device device(o.common.deviceOptions());
  const gpu::Context& context = runtime::Access::context(device);
  const gpu::PipelineCache& cache = runtime::Access::pipelineCache(device);
  std::unique_ptr<render::VolumeSequence> sequence;
  nlohmann::json provenance;
  if (scene) {
    sequence =
        withinDeviceLimits(o.scene.string(), scene->vdb ? "vdb.voxels" : gridSetting(scene->grid), [&] {
          return modes::openSceneVolumes(context, cache, *scene, o.first + frameCount, o.scene.string());
        });
    provenance["source"] = {{"scene", fs::absolute(o.scene).string()}};
    if (scene->vdb) provenance["source"].update(modes::describeSource(*sequence));
  } else {
    auto vdb = withinDeviceLimits("--voxels " + std::to_string(o.voxels.value_or(128)), "--voxels", [&] {
      return std::make_unique<reference::VdbSequence>(context, o.vdb, o.voxels.value_or(128),
                                                      smoke.emission.intensity > 0.0f);
    });
    nlohmann::json files = nlohmann::json::array();
    for (const fs::path& f : o.vdb) files.push_back(fs::absolute(f).string());
    const render::VolumeGrid& lattice = vdb->lattice();
    provenance["source"] = {{"vdb", files},
                            {"lattice",
                             {{"cells", {lattice.size.x, lattice.size.y, lattice.size.z}},
                              {"origin", {lattice.origin.x, lattice.origin.y, lattice.origin.z}},
                              {"cell_size", lattice.cellSize}}}};
    sequence = std::move(vdb);
  }

  reference::FlipbookBake job;
  job.firstFrame = o.first;
  job.frameCount = frameCount;
  job.columns = o.columns.value_or(0);
  job.packing = reference::packingPreset(o.packing);
  job.emissiveMask = o.emissive == "mask";
  job.camera = chooseCamera(o, scene ? &*scene : nullptr, sequence->bounds());
  job.smoke = smoke;
  job.settings.width = tileWidth;
  job.settings.height = tileHeight;
  if (o.step) job.settings.stepCells = *o.step;
  if (o.lightSpacing) job.settings.lightSpacingCells = *o.lightSpacing;
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
  job.provenance = provenance;

  // The bake is written into a staging directory and moved in when it has succeeded: an earlier bake stays
  // whole until then, and a directory made for this bake goes again if it fails or is stopped.
  StagedDirectory output(o.out, "bake", o.force, isBakeOutput, kBakeFolders);
  job.out = output.staging();
  std::printf("sixway bake: %d frames, tiles of %dx%d, %s scattering, packing %s: %s\n", job.frameCount,
              tileWidth, tileHeight, reference::scatteringName(job.scattering), o.packing.c_str(),
              describePacking(job.packing).c_str());
  std::fflush(stdout);
  // The camera's errors name where it came from: the --camera-* options, else the scene (or the VDB files'
  // framing, which sees the whole volume).
  const fs::path cameraSource = !o.cameraPosition.empty() ? fs::path("--camera-position")
                                : !o.scene.empty()        ? o.scene
                                                          : fs::path("--vdb");
  std::vector<MemoryRow> memory;
  memory.reserve(size_t(frameCount));
  reference::FlipbookBakeResult result;
  throwIfStopped();  // a signal while the sequence was being loaded or simulated
  output.underFinalNames([&] {
    result = namingScene(o.scene, cameraSource, [&] {
      return withinDeviceLimits("--tile", "--tile", [&] {
        return reference::bakeFlipbook(context, cache, *sequence, job, [&](const std::string& line) {
          std::printf("  %s\n", line.c_str());
          std::fflush(stdout);
          const gpu::MemoryUse device = context.memoryUse();
          memory.push_back({device.bytes, device.allocations, residentSetBytes()});
          throwIfStopped();
        });
      });
    });
  });
  output.commit();
  if (const auto* vdb = dynamic_cast<const reference::VdbSequence*>(sequence.get()))
    for (const std::string& note : vdb->notes()) std::fprintf(stderr, "sixway: note: %s\n", note.c_str());
  std::printf("sixway bake: wrote %s\n", (output.directory() / result.sidecar.filename()).string().c_str());
  // What a Unity VFX Graph output needs besides the textures (their .meta files hold the import settings).
  std::printf("sixway bake: Unity: Flip Book Size %d x %d, %d frames; textures linear, RGBA half (EXR)\n",
              result.layout.columns, result.layout.rows, result.layout.frames);
  printEmissiveSettings(result.emissiveMask, job.emissiveMask);
  if (!o.report.empty()) {
    const uint64_t heldPerFrame =
        uint64_t(tileWidth) * uint64_t(tileHeight) * render::sixWayChannelNames().size() * sizeof(float);
    io::writeReport(o.report, {{"out", fs::absolute(o.out).string()},
                               {"device", context.properties().deviceName},
                               {"tile", {tileWidth, tileHeight}},
                               {"scattering", reference::scatteringName(job.scattering)},
                               {"held_bytes_per_frame", heldPerFrame},
                               {"frames", frameRows(memory, result, job.firstFrame)}});
  }
  requireNoValidationMessages(device);
}

}  // namespace

void addBakeCommand(CLI::App& app) {
  auto o = std::make_shared<BakeOptions>();
  CLI::App* bake = app.add_subcommand("bake", "Reference six-way lightmaps and a Unity-packed flipbook");
  o->common.addTo(*bake);
  auto* sceneOption =
      bake->add_option("--scene", o->scene, "Scene JSON: bake its simulation")->check(filePath());
  bake->add_option("--vdb", o->vdb, "OpenVDB files, one per frame")->excludes(sceneOption)->check(filePath());
  bake->add_option("--out", o->out, "Output directory")->required()->check(directoryPath());
  bake->add_flag("--force", o->force,
                 "Write into an existing output directory, overwrite an existing report");
  bake->add_option("--report", o->report,
                   "JSON report: per frame the GPU time and the host and device memory in use")
      ->check(filePath());
  bake->add_option("--first", o->first, "First frame baked (default 0)")->check(CLI::Range(0, 100000));
  bake->add_option("--frames", o->frames, "Frames baked (default: every VDB file; 16 for a scene)")
      ->check(CLI::Range(1, 100000));
  bake->add_option("--packing", o->packing,
                   "Channel packing of the two textures: unity (default) | rlt-bbf | o3de (docs/formats.md)")
      ->check(CLI::IsMember(reference::packingPresetNames()));
  bake->add_option("--emissive", o->emissive,
                   "Emissive component: mask (default: Unity's Single Channel emission, settings in the "
                   "sidecar) | premultiplied (sixway's luminance × alpha)")
      ->check(CLI::IsMember({"mask", "premultiplied"}));
  bake->add_option("--columns", o->columns, "Flipbook columns (default: a near-square grid)")
      ->check(CLI::Range(1, reference::kMaxFlipbookSide));
  bake->add_option("--tile", o->tile,
                   "Tile size N or WxH in pixels (default: the scene's lightmap_size, or 128)");
  bake->add_option("--camera-position", o->cameraPosition, "Camera position X Y Z (with --camera-target)")
      ->expected(3);
  bake->add_option("--camera-target", o->cameraTarget, "Point the camera looks at, X Y Z")->expected(3);
  bake->add_option("--camera-up", o->cameraUp, "Camera up X Y Z (default 0 1 0)")->expected(3);
  bake->add_option("--fov", o->fov, "Vertical field of view in degrees (default: the scene's, or 40)")
      ->check(CLI::Range(1.0f, 170.0f));
  bake->add_option("--extinction", o->extinction, "σ_t per unit density, 1/m (default: the scene's, or 20)")
      ->check(positiveNumber());
  bake->add_option("--albedo", o->albedo, "Single-scattering albedo (default: the scene's, or 0.9)")
      ->check(CLI::Range(0.0f, 1.0f));
  bake->add_option("--g", o->g, "Henyey-Greenstein asymmetry (default: the scene's, or 0.2)")
      ->check(CLI::Range(-0.99f, 0.99f));
  bake->add_option("--emission", o->emission,
                   "Emission intensity (VDB: with a built-in black-body-like ramp)")
      ->check(nonNegativeNumber());
  bake->add_option("--voxels", o->voxels,
                   "VDB: cells along the longest axis of the resampled lattice (default 128, or the scene's "
                   "vdb.voxels)")
      ->check(CLI::Range(2, 1024));
  bake->add_option("--step", o->step, "Longest march step in cells (default 0.5)")
      ->check(CLI::Range(0.01f, 0.5f));
  bake->add_option("--light-spacing", o->lightSpacing, "Light-grid spacing in cells (default 1)")
      ->check(CLI::Range(0.1f, 8.0f));
  bake->add_option("--scattering", o->scattering,
                   "multiple (default: exact single scattering + path-traced higher orders) | single");
  bake->add_option("--spp", o->samples, "Multiple scattering: samples per traced pixel (default 64)")
      ->check(CLI::Range(1, 1 << 20));
  bake->add_option("--orders", o->orders, "Multiple scattering: scattering orders (default 64)")
      ->check(CLI::Range(2, 100000));
  bake->add_option(
      "--ms-downsample", o->downsample,
      "Multiple scattering: orders >= 2 traced at 1/N of the tile size, N = 1, 2, 4, 8 (default 1)");
  bake->add_flag("--ms-all-orders", o->traceAllOrders,
                 "Multiple scattering: every order path-traced at full resolution (slow; the reference)");
  bake->add_option("--seed", o->seed, "Multiple scattering: random seed (default: the scene's, or 1)");
  bake->callback([o] { run(*o); });
}

}  // namespace sixway::app
