#include "app/bench_command.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "app/bench_options.h"
#include "app/bench_scene.h"
#include "app/shipped_weights.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "io/error.h"
#include "io/file_access.h"
#include "io/json_text.h"
#include "io/report.h"
#include "nn/graph.h"
#include "runtime/internal.h"
#include "runtime/network_weights.h"

namespace sixway::app {
namespace {

// One benchmarked group of stages: its name (in --sections and the report) and what measures it.
struct BenchSection {
  const char* name;
  bool needsWeights;
  std::function<nlohmann::json(const gpu::Context&, const gpu::PipelineCache&, const BenchOptions&,
                               const BenchInputs&)>
      run;
};

const std::vector<BenchSection> kSections = {{"sim", false, benchSimulation},
                                             {"lightmaps", true, benchLightmaps},
                                             {"frame", true, benchFrame},
                                             {"network", true, benchNetwork}};

std::string knownSections() {
  std::string names;
  for (const BenchSection& s : kSections) names += (names.empty() ? "" : ", ") + std::string(s.name);
  return names;
}

// "64x128x64" → (64, 128, 64); throws io::InputError naming --grid. Each axis is read with overflow checked
// (sscanf's %d wrapped 4294967312 to 16).
glm::ivec3 parseLattice(const std::string& text) {
  const auto malformed = [&text] {
    return io::InputError("--grid", "expected NXxNYxNZ, e.g. 64x128x64 (got \"" + text + "\")");
  };
  glm::ivec3 n(0);
  const char* cursor = text.data();
  const char* end = text.data() + text.size();
  for (int axis = 0; axis < 3; ++axis) {
    if (axis > 0 && (cursor == end || *cursor++ != 'x')) throw malformed();
    const auto [next, error] = std::from_chars(cursor, end, n[axis]);
    if (error == std::errc::result_out_of_range)
      throw io::InputError("--grid " + text, "axis " + std::string(1, "xyz"[axis]) +
                                                 " is more than 2048 cells; reduce its size");
    if (error != std::errc() || next == cursor) throw malformed();
    cursor = next;
  }
  if (cursor != end) throw malformed();
  if (glm::any(glm::lessThan(n, glm::ivec3(8))))
    throw io::InputError("--grid " + text, "every axis needs at least 8 cells");
  if (glm::any(glm::greaterThan(n, glm::ivec3(2048))))
    throw io::InputError("--grid " + text, "an axis has more than 2048 cells; reduce its size");
  if (uint64_t(n.x) * uint64_t(n.y) * uint64_t(n.z) > (uint64_t(1) << 31))
    throw io::InputError("--grid " + text, "more than 2^31 cells; reduce its size");
  return n;
}

void requireAtLeast(const char* option, int value, int least) {
  if (value < least)
    throw io::InputError(
        option, "must be at least " + std::to_string(least) + " (got " + std::to_string(value) + ")");
}

void requireLightmapSize(const char* option, uint32_t size) {
  if (size < 16 || size > 4096 || size % 16 != 0)
    throw io::InputError(
        option, "a lightmap size is a multiple of 16 from 16 to 4096 (got " + std::to_string(size) + ")");
}

// The options checked and the inputs read before any section runs: bad input fails in a second, not after
// minutes of benchmarks.
BenchInputs prepare(BenchOptions& o) {
  std::vector<std::string> sections;
  for (const std::string& name : o.sections) {
    const auto known = std::find_if(kSections.begin(), kSections.end(),
                                    [&](const BenchSection& s) { return name == s.name; });
    if (known == kSections.end())
      throw io::InputError("--sections", "unknown section \"" + name + "\" (known: " + knownSections() + ")");
    if (std::find(sections.begin(), sections.end(), name) == sections.end()) sections.push_back(name);
  }
  if (sections.empty())
    throw io::InputError("--sections", "names no section (known: " + knownSections() + ")");
  o.sections = sections;
  requireAtLeast("--warmup", o.warmup, 0);
  requireAtLeast("--repeats", o.repeats, 1);
  requireAtLeast("--repeats-large", o.repeatsLarge, 1);
  requireAtLeast("--sim-steps", o.simSteps, 1);
  if (o.simSteps > 64)
    throw io::InputError("--sim-steps",
                         "at most 64 steps per submission (got " + std::to_string(o.simSteps) + ")");
  for (const std::string& storage : o.populationStorages)
    if (storage != "fp32" && storage != "fp16")
      throw io::InputError("--population-storage", "unknown storage \"" + storage + "\" (known: fp32, fp16)");
  for (const std::string& transport : o.smokeTransports)
    if (transport != "sparse" && transport != "dense")
      throw io::InputError("--smoke-transport",
                           "unknown transport \"" + transport + "\" (known: sparse, dense)");
  if (o.tiling != "device" && o.tiling != "blocks" && o.tiling != "pixels" && o.tiling != "matrix")
    throw io::InputError("--tiling",
                         "unknown tiling \"" + o.tiling + "\" (known: device, blocks, pixels, matrix)");
  for (uint32_t size : o.sizes) requireLightmapSize("--size", size);
  requireLightmapSize("--frame-lightmaps", o.frameLightmapSize);
  if (!o.report.empty()) io::requireWritableFile(o.report, o.force);

  BenchInputs inputs;
  for (const std::string& grid : o.grids) inputs.lattices.push_back(parseLattice(grid));
  benchScene(o.scene, inputs.lattices.front());  // the scene file parses
  const bool needsWeights = std::any_of(kSections.begin(), kSections.end(), [&](const BenchSection& s) {
    return s.needsWeights && std::find(sections.begin(), sections.end(), s.name) != sections.end();
  });
  if (needsWeights) {
    inputs.weights = runtime::readWeights(o.weights);
    nn::parseGraph(inputs.weights);  // the graph is valid
  }
  return inputs;
}

// The machine, for the report: a number is only comparable with the machine and its load named.
nlohmann::json machine() {
  std::string cpu = "unknown";
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);)
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  return {{"cpu", cpu}, {"logical_cores", std::thread::hardware_concurrency()}};
}

nlohmann::json loadAverage() {
  double load[3] = {0, 0, 0};
  if (getloadavg(load, 3) != 3) return nullptr;
  return {load[0], load[1], load[2]};
}

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

void run(BenchOptions& o) {
  o.weights = resolveWeights(o.weights);
  const BenchInputs inputs = prepare(o);
  const Device device(o.common.deviceOptions());
  const gpu::Context& context = runtime::Access::context(device);
  const gpu::PipelineCache& cache = runtime::Access::pipelineCache(device);
  const uint32_t api = context.properties().apiVersion;
  const std::string vulkan = std::to_string(VK_API_VERSION_MAJOR(api)) + "." +
                             std::to_string(VK_API_VERSION_MINOR(api)) + "." +
                             std::to_string(VK_API_VERSION_PATCH(api));
  const nlohmann::json host = machine(), loadStart = loadAverage();
  std::printf("device: %s (%s %s), Vulkan %s; %s, %u logical cores, load average %s\n",
              context.properties().deviceName, context.driver().driverName, context.driver().driverInfo,
              vulkan.c_str(), host["cpu"].get<std::string>().c_str(), host["logical_cores"].get<unsigned>(),
              io::jsonText(loadStart).c_str());
  std::printf("bench scene %s; warm-up %d, repeats %d (%d for lattices over %.1f M cells)\n\n",
              o.scene.string().c_str(), o.warmup, o.repeats, o.repeatsLarge, kLargeLatticeCells * 1e-6);
  std::fflush(stdout);
  nlohmann::json report = {
      {"device", context.properties().deviceName},
      {"driver", std::string(context.driver().driverName) + " " + context.driver().driverInfo},
      {"vulkan", vulkan},
      {"machine", host},
      {"date_utc", utcNow()},
      {"load_average_start", loadStart},
      {"scene", o.scene.string()},
      {"warmup", o.warmup},
      {"repeats", o.repeats},
      {"repeats_large", o.repeatsLarge},
      {"sim_steps", o.simSteps},
      {"sections", o.sections}};
  const auto start = std::chrono::steady_clock::now();
  for (const BenchSection& section : kSections)
    if (std::find(o.sections.begin(), o.sections.end(), section.name) != o.sections.end())
      report[section.name] = section.run(context, cache, o, inputs);
  report["load_average_end"] = loadAverage();
  report["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!o.report.empty()) {
    io::writeReport(o.report, report);
    std::printf("\nwrote %s\n", o.report.string().c_str());
  }
  requireNoValidationMessages(device);
}

}  // namespace

void addBenchCommand(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* command = app.add_subcommand("bench", "Per-stage GPU timings at fixed sizes");
  o->common.addTo(*command);
  command->add_option("--report", o->report, "JSON report")->check(filePath());
  command->add_flag("--force", o->force, "Overwrite an existing report");
  command->add_option("--sections", o->sections, "What to time: " + knownSections())
      ->delimiter(',')
      ->capture_default_str();
  command
      ->add_option("--grid", o->grids,
                   "Simulation lattices NXxNYxNZ (the first also for lightmaps and frame)")
      ->capture_default_str();
  command->add_option("--size", o->sizes, "Square lightmap sizes in pixels (lightmaps and network)")
      ->capture_default_str();
  command->add_option("--frame-lightmaps", o->frameLightmapSize, "Lightmap size of the end-to-end frame")
      ->capture_default_str();
  command->add_option("--weights", o->weights, kWeightsHelp)->check(filePath());
  command->add_option("--warmup", o->warmup, "Untimed runs first (at most 1 for the large lattices)")
      ->capture_default_str();
  command->add_option("--repeats", o->repeats, "Timed runs (median, min and max are reported)")
      ->capture_default_str();
  command
      ->add_option("--repeats-large", o->repeatsLarge,
                   "Timed runs of lattices over 2 M cells (128x256x128: seconds per step on lavapipe)")
      ->capture_default_str();
  command
      ->add_option("--sim-steps", o->simSteps, "Lattice steps per timed submission of the sim section (1-64)")
      ->capture_default_str();
  command
      ->add_option("--population-storage", o->populationStorages,
                   "Sim section: the lattice's population storage, fp32 and/or fp16 (each lattice with each)")
      ->delimiter(',')
      ->capture_default_str();
  command
      ->add_option(
          "--smoke-transport", o->smokeTransports,
          "Sim section: the smoke transport, sparse (the scene's threshold) and/or dense (each with each)")
      ->delimiter(',')
      ->capture_default_str();
  command->add_flag("--fp16", o->fp16,
                    "Network and frame sections: fp16 feature maps (arithmetic stays fp32; the frame's only "
                    "where the device has 16-bit storage)");
  command
      ->add_option("--tiling", o->tiling,
                   "Network section: work per invocation, blocks (lavapipe's best), pixels (a GPU's), matrix "
                   "(pixels, with the conv2d layers of fp16 maps on cooperative matrices) or device")
      ->capture_default_str();
  command->callback([o] { run(*o); });
}

}  // namespace sixway::app
