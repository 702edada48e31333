#include "app/bake_command.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "app/bake_job.h"
#include "app/bake_options.h"
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
#include "reference/bake_flipbook.h"
#include "reference/flipbook.h"
#include "reference/vdb_sequence.h"
#include "runtime/internal.h"
#include "scene/scene.h"

namespace sixway::app {
namespace {

namespace fs = std::filesystem;

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

// --voxels: a cell count (2..1024, CLI11's range message) or "native" (scene::kNativeVoxels).
CLI::Validator voxelCount() {
  return CLI::Validator(
      [](std::string& value) -> std::string {
        if (value == "native") {
          value = std::to_string(scene::kNativeVoxels);
          return "";
        }
        int count = 0;
        const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), count);
        if (error != std::errc() || end != value.data() + value.size())
          return "must be a cell count or native (got " + value + ")";
        if (count < 2 || count > scene::kMaxVdbVoxels)
          return "Value " + value + " not in range 2 to " + std::to_string(scene::kMaxVdbVoxels);
        return "";
      },
      "");
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

// Outputs are checked before any work: a directory or special file under a name the bake replaces stops it
// here.
void checkOptions(const BakeOptions& o) {
  if (o.scene.empty() && o.vdb.empty()) throw io::InputError("bake", "give --scene S or --vdb F...");
  if (o.cameraPosition.empty() != o.cameraTarget.empty())
    throw io::InputError("--camera-position", "--camera-position and --camera-target go together");
  // A tile covers the smoke's billboard: a camera's field of view changes nothing but the framing camera's
  // distance from VDB files.
  if (o.fov && (!o.cameraPosition.empty() || !o.scene.empty()))
    throw io::InputError("--fov", "sets the framing camera of --vdb files only; with " +
                                      std::string(o.scene.empty() ? "--camera-position" : "--scene") +
                                      " the tile covers the smoke's billboard whatever the field of view");
  StagedDirectory::requireWritable(o.out, o.force, isBakeOutput, kBakeFolders);
  if (!o.report.empty()) io::requireWritableFile(o.report, o.force);
}

void printHeading(const reference::FlipbookBake& job, const std::string& packing) {
  std::printf("sixway bake: %d frames, tiles of %dx%d, %s scattering, packing %s: %s\n", job.frameCount,
              job.settings.width, job.settings.height, reference::scatteringName(job.scattering),
              packing.c_str(), describePacking(job.packing).c_str());
  std::fflush(stdout);
}

// The bake into `output`'s staging directory, a line per frame with the memory in use after it recorded in
// `memory`.
reference::FlipbookBakeResult bake(const gpu::Context& context, const gpu::PipelineCache& cache,
                                   const BakeOptions& o, render::VolumeSequence& sequence,
                                   const reference::FlipbookBake& job, StagedDirectory& output,
                                   std::vector<MemoryRow>& memory) {
  // The camera's errors name where it came from: the --camera-* options, else the scene (or the VDB files'
  // framing, which sees the whole volume).
  const fs::path cameraSource = !o.cameraPosition.empty() ? fs::path("--camera-position")
                                : !o.scene.empty()        ? o.scene
                                                          : fs::path("--vdb");
  reference::FlipbookBakeResult result;
  output.underFinalNames([&] {
    result = namingScene(o.scene, cameraSource, [&] {
      return withinDeviceLimits("--tile", "--tile", [&] {
        return reference::bakeFlipbook(context, cache, sequence, job, [&](const std::string& line) {
          std::printf("  %s\n", line.c_str());
          std::fflush(stdout);
          const gpu::MemoryUse device = context.memoryUse();
          memory.push_back({device.bytes, device.allocations, residentSetBytes()});
          throwIfStopped();
        });
      });
    });
  });
  return result;
}

void printResult(const StagedDirectory& output, const render::VolumeSequence& sequence,
                 const reference::FlipbookBakeResult& result, const reference::FlipbookBake& job) {
  if (const auto* vdb = dynamic_cast<const reference::VdbSequence*>(&sequence))
    for (const std::string& note : vdb->notes()) std::fprintf(stderr, "sixway: note: %s\n", note.c_str());
  std::printf("sixway bake: wrote %s\n", (output.directory() / result.sidecar.filename()).string().c_str());
  // What a Unity VFX Graph output needs besides the textures (their .meta files hold the import settings).
  std::printf("sixway bake: Unity: Flip Book Size %d x %d, %d frames; textures linear, RGBA half (EXR)\n",
              result.layout.columns, result.layout.rows, result.layout.frames);
  printEmissiveSettings(result.emissiveMask, job.emissiveMask);
}

void writeBakeReport(const BakeOptions& o, const gpu::Context& context, const reference::FlipbookBake& job,
                     const reference::FlipbookBakeResult& result, const std::vector<MemoryRow>& memory) {
  const uint64_t heldPerFrame = uint64_t(job.settings.width) * uint64_t(job.settings.height) *
                                render::sixWayChannelNames().size() * sizeof(float);
  io::writeReport(o.report, {{"out", fs::absolute(o.out).string()},
                             {"device", context.properties().deviceName},
                             {"tile", {job.settings.width, job.settings.height}},
                             {"scattering", reference::scatteringName(job.scattering)},
                             {"held_bytes_per_frame", heldPerFrame},
                             {"frames", frameRows(memory, result, job.firstFrame)}});
}

void run(const BakeOptions& o) {
  const StopOnSignal stopOnSignal;
  checkOptions(o);
  std::optional<scene::Scene> scene = bakedScene(o);
  scene::Scene* const baked = scene ? &*scene : nullptr;
  const scene::Smoke smoke = bakedSmoke(o, baked);
  const BakeTile tile = bakedTile(o, baked);
  // The flipbook's size is known before anything is simulated or loaded.
  const int frameCount = bakedFrameCount(o, baked, tile);

  const Device device(o.common.deviceOptions());
  const gpu::Context& context = runtime::Access::context(device);
  const gpu::PipelineCache& cache = runtime::Access::pipelineCache(device);
  const BakeSource source = openBakeSource(context, cache, o, baked, smoke, frameCount);
  reference::FlipbookBake job = bakeJob(o, baked, source, smoke, tile, frameCount);

  // The bake is written into a staging directory and moved in when it has succeeded: an earlier bake stays
  // whole until then, and a directory made for this bake goes again if it fails or is stopped.
  StagedDirectory output(o.out, "bake", o.force, isBakeOutput, kBakeFolders);
  job.out = output.staging();
  printHeading(job, o.packing);
  std::vector<MemoryRow> memory;
  memory.reserve(size_t(frameCount));
  throwIfStopped();  // a signal while the sequence was being loaded or simulated
  const reference::FlipbookBakeResult result = bake(context, cache, o, *source.sequence, job, output, memory);
  output.commit();
  printResult(output, *source.sequence, result, job);
  if (!o.report.empty()) writeBakeReport(o, context, job, result, memory);
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
  bake->add_option("--fov", o->fov,
                   "Vertical field of view in degrees of the framing camera for --vdb files (default 40; a "
                   "given camera's changes nothing: the tile covers the smoke's billboard)")
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
  bake->add_option("--density-grid", o->densityGrid,
                   "VDB: the density grid's name (default density; density_noise: a Blender cache's noise)")
      ->excludes(sceneOption);
  bake->add_option("--voxels", o->voxels,
                   "VDB: cells along the longest axis of the files' active box (default 128, or the scene's "
                   "vdb.voxels), or native: the files' own voxels; one empty cell is added on each side")
      ->transform(voxelCount())
      ->type_name("N|native");
  bake->add_option("--step", o->step, "Longest march step in cells (default 0.5)")
      ->check(CLI::Range(0.01f, 0.5f));
  bake->add_option(
          "--light-spacing", o->lightSpacing,
          "Light-grid spacing in cells (default: 0.5 / the optical depth of the densest cell, within "
          "0.25..1)")
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
