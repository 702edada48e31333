// `sixway bench` section "network": the lightmap network alone with a timed stage per layer (a
// NAFBlock is four), on a synthetic guide (the network's cost does not depend on the values), FLOPs counted
// from the graph (docs/benchmarks.md, "Neural inference"). The same network recorded as one timed stage runs
// alternately with it: on lavapipe the per-layer stages were seen to add up to much less than the whole.
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "app/bench_options.h"
#include "app/bench_stats.h"
#include "gpu/context.h"
#include "gpu/image.h"
#include "gpu/sequence.h"
#include "nn/network.h"
#include "scene/scene.h"

namespace sixway::app {
namespace {

// CPU time of the whole process (all threads: lavapipe runs the work on its own threads), in milliseconds.
double processCpuMs() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return (usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) * 1e3 +
         (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-3;
}

// A smooth guide-like image.
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

// An emission for a 5-channel guide: a smaller blob.
gpu::Image benchEmission(const gpu::Context& context, uint32_t size) {
  gpu::Image emission(context, {size, size, 1, VK_FORMAT_R32_SFLOAT,
                                VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT, "guide emission"});
  std::vector<float> texels(size_t(size) * size);
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) {
      const float u = (x + 0.5f) / size - 0.5f, v = (y + 0.5f) / size - 0.6f;
      texels[size_t(y) * size + x] = 0.5f * std::exp(-30.0f * (u * u + v * v));
    }
  emission.upload(std::as_bytes(std::span(texels)));
  return emission;
}

nn::NetworkOptions benchNetworkOptions(const BenchOptions& o) {
  const nn::Tiling tiling = o.tiling == "blocks"   ? nn::Tiling::Blocks
                            : o.tiling == "pixels" ? nn::Tiling::Pixels
                            : o.tiling == "matrix" ? nn::Tiling::Matrix
                                                   : nn::Tiling::Device;
  nn::NetworkOptions options{o.fp16 ? nn::Precision::Fp16 : nn::Precision::Fp32, true, tiling};
  options.albedo = scene::Smoke{}.albedo;  // a network that reads it sees a scene's default smoke
  return options;
}

// A timed stage, in record order: a layer, or a part of a layer that has parts.
struct LayerStage {
  std::string name, kind;
  double flops;
  std::vector<double> ms;
};

std::vector<LayerStage> layerStages(const nn::Network& network) {
  std::vector<LayerStage> stages;
  for (const nn::LayerInfo& layer : network.layers()) {
    if (layer.parts.empty()) stages.push_back({layer.name, layer.kind, layer.flops, {}});
    for (const auto& part : layer.parts)
      stages.push_back({layer.name + "/" + part.name, layer.kind + "/" + part.name, part.flops, {}});
  }
  return stages;
}

// The timed runs, the network as one stage and layer by layer alternately: the stages' times into `stages`.
struct NetworkRuns {
  std::vector<double> totals;  // the layers' times added up
  std::vector<double> cpuMs;   // the process's CPU time of the layer-by-layer run
  std::vector<double> wholeMs;
};

NetworkRuns timeRuns(gpu::Sequence& layers, gpu::Sequence& whole, std::vector<LayerStage>& stages,
                     int repeats) {
  NetworkRuns runs;
  for (int r = 0; r < repeats; ++r) {
    whole.submit();
    runs.wholeMs.push_back(whole.stageTimes().front().milliseconds);
    const double cpuBefore = processCpuMs();
    layers.submit();
    runs.cpuMs.push_back(processCpuMs() - cpuBefore);
    double total = 0.0;
    for (size_t i = 0; i < stages.size(); ++i) {
      stages[i].ms.push_back(layers.stageTimes().at(i).milliseconds);
      total += stages[i].ms.back();
    }
    runs.totals.push_back(total);
  }
  return runs;
}

// Each stage's median time and rate, the same added up per kind (a part also under its layer's kind), and
// the FLOPs of them all.
struct LayerFigures {
  nlohmann::json layers = nlohmann::json::array();
  std::map<std::string, std::pair<double, double>> byKind;  // kind -> (ms, flops)
  double flops = 0.0;
};

LayerFigures layerFigures(const std::vector<LayerStage>& stages) {
  LayerFigures figures;
  for (const LayerStage& stage : stages) {
    const double ms = summarize(stage.ms).median;
    figures.layers.push_back({{"name", stage.name},
                              {"kind", stage.kind},
                              {"ms", ms},
                              {"flops", stage.flops},
                              {"gflops_per_s", stage.flops / ms * 1e-6}});
    for (const std::string& kind : {stage.kind, stage.kind.substr(0, stage.kind.find('/'))}) {
      figures.byKind[kind].first += ms;
      figures.byKind[kind].second += stage.flops;
      if (kind == stage.kind.substr(0, stage.kind.find('/'))) break;
    }
    figures.flops += stage.flops;
  }
  return figures;
}

nlohmann::json kindReport(const LayerFigures& figures) {
  nlohmann::json report = nlohmann::json::object();
  for (const auto& [kind, msFlops] : figures.byKind)
    report[kind] = {{"ms", msFlops.first},
                    {"flops", msFlops.second},
                    {"gflops_per_s", msFlops.second / msFlops.first * 1e-6}};
  return report;
}

void printNetworkTimes(const nn::Network& network, const BenchOptions& o, uint32_t size,
                       const NetworkRuns& runs, const LayerFigures& figures) {
  const Timing total = summarize(runs.totals);
  const Timing whole = summarize(runs.wholeMs);
  std::printf(
      "\n%ux%u, %s maps, %s tiling: layers add up to %.2f ms (median of %d; min %.2f, max %.2f), %.2f GFLOP, "
      "%.1f "
      "GFLOP/s; "
      "process CPU time %.2f ms; as one stage %.2f ms (min %.2f, max %.2f)\n",
      size, size, o.fp16 ? "fp16" : "fp32", nn::tilingName(network.tiling()), total.median, o.repeats,
      total.min, total.max, figures.flops * 1e-9, figures.flops / total.median * 1e-6,
      summarize(runs.cpuMs).median, whole.median, whole.min, whole.max);
  std::printf("  %-24s %-20s %9s %9s\n", "layer", "kind", "ms", "GFLOP/s");
  for (const auto& l : figures.layers)
    std::printf("  %-24s %-20s %9.3f %9.1f\n", l["name"].get<std::string>().c_str(),
                l["kind"].get<std::string>().c_str(), l["ms"].get<double>(), l["gflops_per_s"].get<double>());
  std::printf("  per layer type:\n");
  for (const auto& [kind, msFlops] : figures.byKind)
    std::printf("  %-45s %9.3f %9.1f\n", kind.c_str(), msFlops.first, msFlops.second / msFlops.first * 1e-6);
  std::fflush(stdout);
}

nlohmann::json benchNetworkSize(const gpu::Context& context, const gpu::PipelineCache& cache,
                                const io::SafetensorsFile& weights, const BenchOptions& o, uint32_t size) {
  nn::Network network(context, cache, weights, size, size, benchNetworkOptions(o));
  const gpu::Image guide = benchGuide(context, size), emission = benchEmission(context, size);
  const gpu::ImageDesc lightmap{size,
                                size,
                                1,
                                VK_FORMAT_R16G16B16A16_SFLOAT,
                                VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                "lightmap"};
  const gpu::Image a(context, lightmap), b(context, lightmap);
  gpu::Sequence layers(context, network.stageCount());
  network.record(layers, {guide, &emission}, a, b, true);
  gpu::Sequence whole(context);
  whole.beginStage("network");
  network.record(whole, {guide, &emission}, a, b);
  whole.endStage();
  whole.finish();
  for (int i = 0; i < o.warmup; ++i) {
    layers.submit();
    whole.submit();
  }
  std::vector<LayerStage> stages = layerStages(network);
  const NetworkRuns runs = timeRuns(layers, whole, stages, o.repeats);
  const LayerFigures figures = layerFigures(stages);
  printNetworkTimes(network, o, size, runs, figures);
  const double total = summarize(runs.totals).median;
  return {{"size", size},
          {"tiling", nn::tilingName(network.tiling())},
          {"total_ms", total},
          {"total", timingJson(runs.totals)},
          {"whole", timingJson(runs.wholeMs)},
          {"process_cpu_ms", summarize(runs.cpuMs).median},
          {"flops", figures.flops},
          {"gflops_per_s", figures.flops / total * 1e-6},
          {"layers", figures.layers},
          {"by_kind", kindReport(figures)}};
}

}  // namespace

nlohmann::json benchNetwork(const gpu::Context& context, const gpu::PipelineCache& cache,
                            const BenchOptions& o, const BenchInputs& inputs) {
  std::printf("\nneural lightmaps, layer by layer: %s\n", o.weights.string().c_str());
  nlohmann::json sizes = nlohmann::json::array();
  for (uint32_t size : o.sizes) sizes.push_back(benchNetworkSize(context, cache, inputs.weights, o, size));
  return {{"weights", o.weights.string()},
          {"precision", o.fp16 ? "fp16" : "fp32"},
          {"warmup", o.warmup},
          {"repeats", o.repeats},
          {"sizes", sizes}};
}

}  // namespace sixway::app
