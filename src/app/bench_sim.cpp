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

nlohmann::json benchLattice(const gpu::Context& context, const gpu::PipelineCache& cache,
                            const BenchOptions& o, glm::ivec3 lattice, const std::string& storage,
                            const std::string& transport) {
  scene::Scene scene = benchScene(o.scene, lattice);
  scene.fluid.populationStorage =
      storage == "fp16" ? scene::PopulationStorage::Fp16 : scene::PopulationStorage::Fp32;
  scene.smoke.sparse = transport == "sparse";
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
  std::unique_ptr<sim::Simulation> simulation;
  try {
    simulation = std::make_unique<sim::Simulation>(context, cache, scene);
  } catch (const gpu::GpuError& e) {  // a lattice the device cannot hold: bad input, not a crash
    throw io::InputError("--grid " + latticeName(lattice), e.what());
  }
  simulation->smoke().upload(benchSmoke(scene));

  const uint32_t steps = uint32_t(o.simSteps);
  for (int i = 0; i < warmup; ++i) simulation->advance(steps);
  StageTimes step;
  std::vector<double> watchdog, sources, activity, fluxes, limiter,
      update;                        // the smoke's passes, ms per step
  std::vector<double> activeBricks;  // fraction, after each run
  for (int r = 0; r < repeats; ++r) {
    simulation->advance(steps);
    const sim::StepTimes& t = simulation->report().times;
    step.beginRun();
    step.add("obstacles", t.obstacles / steps);
    if (simulation->obstacles().obstacleCount() > 0) step.add("forces", t.forces / steps);
    step.add("lbm", t.lbm / steps);
    step.add("smoke", t.smoke / steps);
    watchdog.push_back(t.watchdog);
    sources.push_back(t.smokePasses.sources / steps);
    activity.push_back(t.smokePasses.activity / steps);
    activeBricks.push_back(double(simulation->smoke().activeBricks()) / double(simulation->smoke().bricks()));
    fluxes.push_back(t.smokePasses.fluxes / steps);
    limiter.push_back(t.smokePasses.limiter / steps);
    update.push_back(t.smokePasses.update / steps);
  }
  step.print("  lattice step " + latticeName(lattice));
  // MLUPs from the step time: the fastest step gives the highest rate.
  const Timing total = summarize(step.totals());
  const Timing lbm = summarize(step.samples("lbm"));
  const auto mlups = [cells](double ms) { return double(cells) / (ms * 1e3); };
  const Timing dog = summarize(watchdog);
  std::printf(
      "  smoke passes (median ms per step): sources %.3f, activity %.3f, FCT fluxes %.3f, limiter %.3f, "
      "update "
      "%.3f; active bricks %.1f%% (median of the runs' last substeps)\n",
      summarize(sources).median, summarize(activity).median, summarize(fluxes).median,
      summarize(limiter).median, summarize(update).median, 100 * summarize(activeBricks).median);
  std::printf(
      "  %.3f MLUPs (min %.3f, max %.3f); LBM pass alone %.3f MLUPs; watchdog %.3f ms per submission\n",
      mlups(total.median), mlups(total.max), mlups(total.min), mlups(lbm.median), dog.median);
  std::fflush(stdout);

  nlohmann::json report = step.json();
  report["size"] = {lattice.x, lattice.y, lattice.z};
  report["cells"] = cells;
  report["population_storage"] = storage;
  report["smoke_transport"] = transport;
  report["sparse_threshold"] = scene.smoke.sparseThreshold;
  report["active_bricks"] = timingJson(activeBricks);
  report["bytes_per_cell_update"] = bytesPerUpdate;
  report["lattice_bytes"] = latticeBytes;
  report["cell_size_m"] = scene.grid.cellSize;
  report["warmup"] = warmup;
  report["steps_per_run"] = o.simSteps;
  report["mlups"] = {{"median", mlups(total.median)}, {"min", mlups(total.max)}, {"max", mlups(total.min)}};
  report["lbm_mlups"] = mlups(lbm.median);
  report["watchdog"] = timingJson(watchdog);
  // Parts of the "smoke" stage above, not stages of their own (the totals count "smoke" once).
  report["smoke_passes"] = {{"sources", timingJson(sources)},
                            {"activity", timingJson(activity)},
                            {"fluxes", timingJson(fluxes)},
                            {"limiter", timingJson(limiter)},
                            {"update", timingJson(update)}};
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
