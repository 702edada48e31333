#include "app/bench_command.h"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/options.h"
#include "app/report.h"
#include "gpu/context.h"
#include "gpu/image.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "io/safetensors.h"
#include "nn/network.h"

namespace sixway::app {
namespace {

struct BenchOptions {
  CommonOptions common;
  std::filesystem::path report;
  bool force = false;
  std::filesystem::path weights = SIXWAY_DEFAULT_BENCH_WEIGHTS;
  std::vector<uint32_t> sizes = {128, 256};
  int warmup = 3, repeats = 10;
  bool fp16 = false;
};

// One benchmarked stage: its name in the report and the function that measures it.
struct BenchSection {
  const char* name;
  std::function<nlohmann::json(const gpu::Context&, const gpu::PipelineCache&, const BenchOptions&)> run;
};

// CPU time of the whole process (all threads: lavapipe runs the work on its own threads), in milliseconds.
double processCpuMs() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return (usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) * 1e3 +
         (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-3;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// A smooth guide-like image (the network's cost does not depend on the values).
gpu::Image benchGuide(const gpu::Context& context, uint32_t size) {
  gpu::Image guide(context, {size, size, 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                             VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT, "guide"});
  std::vector<float> texels(size_t(size) * size * 4);
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) {
      const float u = (x + 0.5f) / size - 0.5f, v = (y + 0.5f) / size - 0.5f;
      const float blob = std::exp(-8.0f * (u * u + v * v));
      float* t = &texels[(size_t(y) * size + x) * 4];
      t[0] = blob, t[1] = std::min(1.0f, 1.5f * blob), t[2] = 0.5f + 0.3f * u, t[3] = 0.0f;
    }
  guide.upload(std::as_bytes(std::span(texels)));
  return guide;
}

nlohmann::json benchNetworkSize(const gpu::Context& context, const gpu::PipelineCache& cache,
                                const io::SafetensorsFile& weights, const BenchOptions& o, uint32_t size) {
  nn::Network network(context, cache, weights, size, size,
                      {o.fp16 ? nn::Precision::Fp16 : nn::Precision::Fp32});
  const gpu::Image guide = benchGuide(context, size);
  const gpu::ImageDesc lightmap{size,
                                size,
                                1,
                                VK_FORMAT_R16G16B16A16_SFLOAT,
                                VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                "lightmap"};
  const gpu::Image a(context, lightmap), b(context, lightmap);
  gpu::Sequence sequence(context, network.stageCount());
  network.record(sequence, guide, a, b, true);
  for (int i = 0; i < o.warmup; ++i) sequence.submit();

  // Stages in record order: one per layer, or one per part of a layer that has parts.
  struct Stage {
    std::string name, kind;
    double flops;
    std::vector<double> ms;
  };
  std::vector<Stage> stages;
  for (const nn::LayerInfo& layer : network.layers()) {
    if (layer.parts.empty()) stages.push_back({layer.name, layer.kind, layer.flops, {}});
    for (const auto& part : layer.parts)
      stages.push_back({layer.name + "/" + part.name, layer.kind + "/" + part.name, part.flops, {}});
  }
  std::vector<double> totals, cpuMs;
  for (int r = 0; r < o.repeats; ++r) {
    const double cpuBefore = processCpuMs();
    sequence.submit();
    cpuMs.push_back(processCpuMs() - cpuBefore);
    double total = 0.0;
    for (size_t i = 0; i < stages.size(); ++i) {
      stages[i].ms.push_back(sequence.stageTimes().at(i).milliseconds);
      total += stages[i].ms.back();
    }
    totals.push_back(total);
  }

  nlohmann::json layerReport = nlohmann::json::array();
  std::map<std::string, std::pair<double, double>>
      byKind;  // kind -> (ms, flops), parts also under their layer's
  double flops = 0.0;
  for (const Stage& stage : stages) {
    const double ms = median(stage.ms);
    layerReport.push_back({{"name", stage.name},
                           {"kind", stage.kind},
                           {"ms", ms},
                           {"flops", stage.flops},
                           {"gflops_per_s", stage.flops / ms * 1e-6}});
    for (const std::string& kind : {stage.kind, stage.kind.substr(0, stage.kind.find('/'))}) {
      byKind[kind].first += ms;
      byKind[kind].second += stage.flops;
      if (kind == stage.kind.substr(0, stage.kind.find('/'))) break;
    }
    flops += stage.flops;
  }
  const double total = median(totals), cpu = median(cpuMs);
  std::printf(
      "\n%ux%u, %s maps: %.2f ms (median of %d), %.2f GFLOP, %.1f GFLOP/s; process CPU time %.2f ms\n", size,
      size, o.fp16 ? "fp16" : "fp32", total, o.repeats, flops * 1e-9, flops / total * 1e-6, cpu);
  std::printf("  %-24s %-20s %9s %9s\n", "layer", "kind", "ms", "GFLOP/s");
  for (const auto& l : layerReport)
    std::printf("  %-24s %-20s %9.3f %9.1f\n", l["name"].get<std::string>().c_str(),
                l["kind"].get<std::string>().c_str(), l["ms"].get<double>(), l["gflops_per_s"].get<double>());
  nlohmann::json kindReport = nlohmann::json::object();
  std::printf("  per layer type:\n");
  for (const auto& [kind, msFlops] : byKind) {
    const double rate = msFlops.second / msFlops.first * 1e-6;
    kindReport[kind] = {{"ms", msFlops.first}, {"flops", msFlops.second}, {"gflops_per_s", rate}};
    std::printf("  %-45s %9.3f %9.1f\n", kind.c_str(), msFlops.first, rate);
  }
  return {{"size", size},          {"total_ms", total},
          {"flops", flops},        {"gflops_per_s", flops / total * 1e-6},
          {"layers", layerReport}, {"by_kind", kindReport}};
}

nlohmann::json benchNetwork(const gpu::Context& context, const gpu::PipelineCache& cache,
                            const BenchOptions& o) {
  const io::SafetensorsFile weights = io::readSafetensors(o.weights);
  std::printf("neural lightmaps: %s\n", o.weights.string().c_str());
  nlohmann::json sizes = nlohmann::json::array();
  for (uint32_t size : o.sizes) sizes.push_back(benchNetworkSize(context, cache, weights, o, size));
  return {{"weights", o.weights.string()},
          {"precision", o.fp16 ? "fp16" : "fp32"},
          {"warmup", o.warmup},
          {"repeats", o.repeats},
          {"sizes", sizes}};
}

// The stages with a benchmark; the simulation and the renderer add theirs here.
const std::vector<BenchSection> kSections = {{"neural", benchNetwork}};

}  // namespace

void addBenchCommand(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* command = app.add_subcommand("bench", "Per-stage GPU timings at fixed sizes");
  o->common.addTo(*command);
  command->add_option("--report", o->report, "JSON report");
  command->add_flag("--force", o->force, "Overwrite an existing report");
  command->add_option("--weights", o->weights, "Network weights (safetensors)")
      ->capture_default_str()
      ->check(CLI::ExistingFile);
  command->add_option("--size", o->sizes, "Square guide sizes in pixels")
      ->capture_default_str()
      ->check(CLI::Range(16, 4096));
  command->add_option("--warmup", o->warmup, "Submits before timing")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command->add_option("--repeats", o->repeats, "Timed submits (the median is reported)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command->add_flag("--fp16", o->fp16, "Feature maps stored as fp16 (arithmetic stays fp32)");
  command->callback([o] {
    if (!o->report.empty()) requireWritable(o->report, o->force);
    gpu::Context context(o->common.contextOptions());
    gpu::PipelineCache cache(context, gpu::defaultPipelineCacheFile(context));
    std::printf("device: %s (%s %s)\n", context.properties().deviceName, context.driver().driverName,
                context.driver().driverInfo);
    nlohmann::json report = {
        {"device", context.properties().deviceName},
        {"driver", std::string(context.driver().driverName) + " " + context.driver().driverInfo}};
    for (const BenchSection& section : kSections) report[section.name] = section.run(context, cache, *o);
    if (!o->report.empty()) writeReport(o->report, report);
    if (context.validationMessageCount() > 0)
      throw std::runtime_error(std::to_string(context.validationMessageCount()) + " validation messages");
  });
}

}  // namespace sixway::app
