// `sixway bench` section "sim": the lattice step of the bench scene at fixed lattice sizes, GPU timestamps of
// each pass (sim/simulation.h StepTimes) and MLUPs (docs/conventions.md, "Metrics"). A run is one submission
// of --sim-steps steps, as the simulation submits a frame's steps at once; times are per step, the watchdog's
// per submission.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include "app/bench_options.h"
#include "app/bench_scene.h"
#include "app/bench_stats.h"
#include "gpu/check.h"
#include "io/error.h"
#include "sim/simulation.h"

namespace sixway::app {
namespace {

std::string latticeName(glm::ivec3 n) {
  return std::to_string(n.x) + "x" + std::to_string(n.y) + "x" + std::to_string(n.z);
}

// The bench scene on `lattice` with the population storage and smoke transport under test.
scene::Scene latticeScene(const BenchOptions& o, glm::ivec3 lattice, const std::string& storage,
                          const std::string& transport) {
  scene::Scene scene = benchScene(o.scene, lattice);
  scene.fluid.populationStorage =
      storage == "fp16" ? scene::PopulationStorage::Fp16 : scene::PopulationStorage::Fp32;
  scene.smoke.sparse = transport == "sparse";
  return scene;
}

std::unique_ptr<sim::Simulation> latticeSimulation(const gpu::Context& context,
                                                   const gpu::PipelineCache& cache,
                                                   const scene::Scene& scene) {
  try {
    return std::make_unique<sim::Simulation>(context, cache, scene);
  } catch (const gpu::GpuError& e) {  // a lattice the device cannot hold: bad input, not a crash
    throw io::InputError("--grid " + latticeName(scene.grid.size), e.what());
  }
}

// The timed runs: the step's stages, and the watchdog's and the smoke passes' times apart.
struct LatticeRuns {
  StageTimes step;
  std::vector<double> watchdog, sources, activity, fluxes, limiter,
      update;                        // the smoke's passes, ms per step
  std::vector<double> activeBricks;  // fraction, after each run
};

LatticeRuns timeLattice(sim::Simulation& simulation, uint32_t steps, int repeats) {
  LatticeRuns runs;
  for (int r = 0; r < repeats; ++r) {
    simulation.advance(steps);
    const sim::StepTimes& t = simulation.report().times;
    runs.step.beginRun();
    runs.step.add("obstacles", t.obstacles / steps);
    if (simulation.obstacles().obstacleCount() > 0) runs.step.add("forces", t.forces / steps);
    runs.step.add("lbm", t.lbm / steps);
    runs.step.add("smoke", t.smoke / steps);
    runs.watchdog.push_back(t.watchdog);
    runs.sources.push_back(t.smokePasses.sources / steps);
    runs.activity.push_back(t.smokePasses.activity / steps);
    runs.activeBricks.push_back(double(simulation.smoke().activeBricks()) /
                                double(simulation.smoke().bricks()));
    runs.fluxes.push_back(t.smokePasses.fluxes / steps);
    runs.limiter.push_back(t.smokePasses.limiter / steps);
    runs.update.push_back(t.smokePasses.update / steps);
  }
  return runs;
}

// MLUPs from a step time.
double mlupsOf(uint64_t cells, double ms) {
  return double(cells) / (ms * 1e3);
}

void printLatticeTimes(glm::ivec3 lattice, uint64_t cells, const LatticeRuns& runs) {
  runs.step.print("  lattice step " + latticeName(lattice));
  // MLUPs from the step time: the fastest step gives the highest rate.
  const Timing total = summarize(runs.step.totals());
  const Timing lbm = summarize(runs.step.samples("lbm"));
  const Timing dog = summarize(runs.watchdog);
  std::printf(
      "  smoke passes (median ms per step): sources %.3f, activity %.3f, FCT fluxes %.3f, limiter %.3f, "
      "update "
      "%.3f; active bricks %.1f%% (median of the runs' last substeps)\n",
      summarize(runs.sources).median, summarize(runs.activity).median, summarize(runs.fluxes).median,
      summarize(runs.limiter).median, summarize(runs.update).median,
      100 * summarize(runs.activeBricks).median);
  std::printf(
      "  %.3f MLUPs (min %.3f, max %.3f); LBM pass alone %.3f MLUPs; watchdog %.3f ms per submission\n",
      mlupsOf(cells, total.median), mlupsOf(cells, total.max), mlupsOf(cells, total.min),
      mlupsOf(cells, lbm.median), dog.median);
  std::fflush(stdout);
}

nlohmann::json benchLattice(const gpu::Context& context, const gpu::PipelineCache& cache,
                            const BenchOptions& o, glm::ivec3 lattice, const std::string& storage,
                            const std::string& transport) {
  const scene::Scene scene = latticeScene(o, lattice, storage, transport);
  const uint64_t cells = uint64_t(lattice.x) * lattice.y * lattice.z;
  const bool large = cells > kLargeLatticeCells;
  const int warmup = large ? std::min(o.warmup, 1) : o.warmup;
  const int repeats = large ? o.repeatsLarge : o.repeats;
  const uint32_t bytesPerUpdate = sim::bytesPerCellUpdate(scene.fluid.populationStorage);
  const uint64_t latticeBytes =
      sim::latticeBytes(scene.grid.size, scene.boundaries.faces, scene.fluid.populationStorage);
  std::printf(
      "simulation %s (%.2f M cells, cell %.4g m), %s populations (%u bytes per update, lattice %.1f MiB), %s "
      "smoke transport: %d warm-up and %d timed runs of %d steps\n",
      latticeName(lattice).c_str(), cells * 1e-6, scene.grid.cellSize, storage.c_str(), bytesPerUpdate,
      latticeBytes / 1048576.0, transport.c_str(), warmup, repeats, o.simSteps);
  std::fflush(stdout);
  const std::unique_ptr<sim::Simulation> simulation = latticeSimulation(context, cache, scene);
  simulation->smoke().upload(benchSmoke(scene));
  const uint32_t steps = uint32_t(o.simSteps);
  for (int i = 0; i < warmup; ++i) simulation->advance(steps);
  const LatticeRuns runs = timeLattice(*simulation, steps, repeats);
  printLatticeTimes(lattice, cells, runs);

  const Timing total = summarize(runs.step.totals());
  nlohmann::json report = runs.step.json();
  report["size"] = {lattice.x, lattice.y, lattice.z};
  report["cells"] = cells;
  report["population_storage"] = storage;
  report["smoke_transport"] = transport;
  report["sparse_threshold"] = scene.smoke.sparseThreshold;
  report["active_bricks"] = timingJson(runs.activeBricks);
  report["bytes_per_cell_update"] = bytesPerUpdate;
  report["lattice_bytes"] = latticeBytes;
  report["cell_size_m"] = scene.grid.cellSize;
  report["warmup"] = warmup;
  report["steps_per_run"] = o.simSteps;
  report["mlups"] = {{"median", mlupsOf(cells, total.median)},
                     {"min", mlupsOf(cells, total.max)},
                     {"max", mlupsOf(cells, total.min)}};
  report["lbm_mlups"] = mlupsOf(cells, summarize(runs.step.samples("lbm")).median);
  report["watchdog"] = timingJson(runs.watchdog);
  // Parts of the "smoke" stage above, not stages of their own (the totals count "smoke" once).
  report["smoke_passes"] = {{"sources", timingJson(runs.sources)},
                            {"activity", timingJson(runs.activity)},
                            {"fluxes", timingJson(runs.fluxes)},
                            {"limiter", timingJson(runs.limiter)},
                            {"update", timingJson(runs.update)}};
  return report;
}

}  // namespace

nlohmann::json benchSimulation(const gpu::Context& context, const gpu::PipelineCache& cache,
                               const BenchOptions& options, const BenchInputs& inputs) {
  nlohmann::json lattices = nlohmann::json::array();
  for (glm::ivec3 lattice : inputs.lattices)
    for (const std::string& storage : options.populationStorages)
      for (const std::string& transport : options.smokeTransports)
        lattices.push_back(benchLattice(context, cache, options, lattice, storage, transport));
  return {{"scene", options.scene.string()},
          {"unit",
           "ms per lattice step, averaged over a submission of steps_per_run steps; the watchdog runs "
           "once per submission"},
          {"lattices", lattices}};
}

}  // namespace sixway::app
