#pragma once
// `sixway bench` (docs/conventions.md, "Command line"): its options and its sections, each timing
// one group of stages at fixed sizes and returning its part of the JSON report.
#include <filesystem>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/options.h"
#include "io/safetensors.h"

namespace sixway::gpu {
class Context;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::app {

struct BenchOptions {
  CommonOptions common;
  std::filesystem::path report;
  bool force = false;
  std::vector<std::string> sections = {"sim", "lightmaps", "frame", "network"};
  std::filesystem::path scene = SIXWAY_BENCH_SCENE;
  std::filesystem::path weights;  // --weights as given (app/shipped_weights.h)
  std::vector<std::string> grids = {"64x128x64", "128x256x128"};  // simulation lattices
  std::vector<uint32_t> sizes = {128, 256, 512};                  // square lightmap sizes
  uint32_t frameLightmapSize = 256;  // the end-to-end frame (the paper's setting)
  int warmup = 2, repeats = 10;
  int repeatsLarge = 3;  // timed runs of lattices over kLargeLatticeCells
  int simSteps = 4;      // lattice steps per submission (a run) of the sim section
  std::vector<std::string> populationStorages = {"fp32"};  // sim section: each lattice with each, in turn
  std::vector<std::string> smokeTransports = {"sparse"};   // sim section: "sparse", "dense"; each with each
  bool fp16 = false;                                       // network and frame sections: fp16 feature maps
  std::string tiling =
      "device";  // network section: work per invocation (nn/kernel.h): device, blocks, pixels, matrix
};

// A lattice larger than this (2 M cells) takes seconds per step on lavapipe: --repeats-large and at most one
// warm-up run.
constexpr uint64_t kLargeLatticeCells = uint64_t(1) << 21;

// What the sections share, read once before any of them runs (so that bad input fails at once).
struct BenchInputs {
  std::vector<glm::ivec3> lattices;  // parsed --grid
  io::SafetensorsFile weights;
};

nlohmann::json benchSimulation(const gpu::Context& context, const gpu::PipelineCache& cache,
                               const BenchOptions& options, const BenchInputs& inputs);
nlohmann::json benchLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache,
                              const BenchOptions& options, const BenchInputs& inputs);
nlohmann::json benchFrame(const gpu::Context& context, const gpu::PipelineCache& cache,
                          const BenchOptions& options, const BenchInputs& inputs);
nlohmann::json benchNetwork(const gpu::Context& context, const gpu::PipelineCache& cache,
                            const BenchOptions& options, const BenchInputs& inputs);

}  // namespace sixway::app
