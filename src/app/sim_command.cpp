#include "app/sim_command.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "app/device_limits.h"
#include "app/options.h"
#include "app/staged_directory.h"
#include "app/stop_on_signal.h"
#include "gpu/bandwidth.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "io/error.h"
#include "io/obj.h"
#include "io/report.h"
#include "io/vdb.h"
#include "render/obstacle_meshes.h"
#include "runtime/internal.h"
#include "sim/simulation.h"
#include "sim/watchdog.h"

namespace sixway::app {
namespace {

namespace fs = std::filesystem;

struct SimOptions {
  CommonOptions common;
  fs::path scene, vdbOut, report;
  uint32_t steps = 0;
  bool force = false;
};

nlohmann::json vec(glm::vec3 v) {
  return {v.x, v.y, v.z};
}

// The files of frame 7 in --vdb-out: "<scene name>_0007.vdb" (the smoke) and, with obstacles,
// "<scene name>_0007.obj" (their triangles then), whatever the name's length.
std::string frameFileName(const std::string& sceneName, int frame, const std::string& extension) {
  std::string number = std::to_string(frame);
  if (number.size() < 4) number.insert(0, 4 - number.size(), '0');
  return sceneName + "_" + number + extension;
}

// Whether `fileName` is a file that `sim --vdb-out` writes for the scene `sceneName`:
// "<scene name>_NNNN.vdb" or ".obj", four digits or more.
bool isFrameFileOf(const std::string& sceneName, const std::string& fileName) {
  const std::string prefix = sceneName + "_";
  for (const std::string suffix : {".vdb", ".obj"}) {
    if (fileName.size() < prefix.size() + 4 + suffix.size()) continue;
    if (!fileName.starts_with(prefix) || !fileName.ends_with(suffix)) continue;
    const std::string number =
        fileName.substr(prefix.size(), fileName.size() - prefix.size() - suffix.size());
    if (std::all_of(number.begin(), number.end(), [](char c) { return c >= '0' && c <= '9'; })) return true;
  }
  return false;
}

// Outputs are checked before any work: an existing directory or report needs --force, and nothing there may
// be a special file where sixway writes a file.
void checkOutputs(const SimOptions& o, const StagedDirectory::OutputNames& vdbFrames) {
  if (!o.vdbOut.empty()) StagedDirectory::requireWritable(o.vdbOut, o.force, vdbFrames);
  if (!o.report.empty()) io::requireWritableFile(o.report, o.force);
}

// What the report collects over the frames.
struct SimTotals {
  nlohmann::json frames = nlohmann::json::array();
  std::vector<nlohmann::json> forcesPerObstacle;  // per obstacle, per step
  double lbmMs = 0, smokeMs = 0, totalMs = 0;
  uint64_t updates = 0;
  int frame = 0;
};

// The frame just simulated (`steps` steps) into the totals; returns its MLUPs.
double recordFrame(SimTotals& totals, const sim::Simulation& simulation, uint32_t steps) {
  const sim::AdvanceReport& r = simulation.report();
  for (size_t s = 0; s < r.forces.size(); ++s)
    for (size_t i = 0; i < r.forces[s].size(); ++i)
      totals.forcesPerObstacle[i].push_back(vec(r.forces[s][i]));
  const double mlups = double(simulation.lbm().cells()) * steps / (r.times.lbm * 1e3);
  totals.lbmMs += r.times.lbm;
  totals.smokeMs += r.times.smoke;
  totals.totalMs += r.times.total();
  totals.updates += simulation.lbm().cells() * steps;
  totals.frames.push_back({{"frame", totals.frame},
                           {"step", simulation.step()},
                           {"time_s", simulation.seconds()},
                           {"smoke_mass", r.smokeMass},
                           {"max_speed_m_s", r.maxSpeed},
                           {"max_lattice_speed", r.maxLatticeSpeed},
                           {"obstacles_ms", r.times.obstacles},
                           {"forces_ms", r.times.forces},
                           {"lbm_ms", r.times.lbm},
                           {"smoke_ms", r.times.smoke},
                           {"watchdog_ms", r.times.watchdog},
                           {"total_ms", r.times.total()},
                           {"mlups", mlups}});
  return mlups;
}

// On a terminal one line updated in place; into a file or pipe one line per frame, without '\r'.
void printFrame(const sim::Simulation& simulation, uint32_t steps, int frame, double mlups, bool terminal) {
  const sim::AdvanceReport& r = simulation.report();
  std::printf(
      "%sstep %6llu/%u  frame %4d  max speed %6.3f m/s (lattice %.3f)  smoke mass %.4g  %6.1f MLUPs%s",
      terminal ? "\r" : "", (unsigned long long)simulation.step(), steps, frame, r.maxSpeed,
      r.maxLatticeSpeed, r.smokeMass, mlups, terminal ? "" : "\n");
  std::fflush(stdout);
}

// The smoke, and the obstacles placed where the simulation has them (render::placedObstacles: the triangles
// the renderers draw and trace, so that another renderer can draw the same frame).
void writeFrameFiles(StagedDirectory& out, sim::Simulation& simulation, const scene::Scene& scene,
                     int frame) {
  auto [density, temperature] = simulation.smokeGrids();
  out.underFinalNames([&] {
    io::writeVdb(out.stagedPath(frameFileName(scene.name, frame, ".vdb")),
                 {{"density", &density}, {"temperature", &temperature}});
    if (!scene.obstacles.empty())
      io::writeObj(out.stagedPath(frameFileName(scene.name, frame, ".obj")),
                   render::placedObstacles(scene.obstacles, simulation.seconds()));
  });
}

// Runs the steps frame by frame; returns "ok", or what stopped the watchdog.
std::string simulate(const SimOptions& o, const scene::Scene& scene, sim::Simulation& simulation,
                     std::optional<StagedDirectory>& vdbOut, SimTotals& totals) {
  const bool terminal = isatty(fileno(stdout));
  std::string watchdog = "ok";
  try {
    while (simulation.step() < o.steps) {
      throwIfStopped();
      const uint32_t n = std::min<uint64_t>(simulation.units().stepsPerFrame, o.steps - simulation.step());
      simulation.advance(n);
      ++totals.frame;
      const double mlups = recordFrame(totals, simulation, n);
      printFrame(simulation, o.steps, totals.frame, mlups, terminal);
      if (vdbOut) writeFrameFiles(*vdbOut, simulation, scene, totals.frame);
    }
  } catch (const sim::WatchdogError& e) {
    watchdog = e.what();
  }
  if (terminal) std::printf("\n");
  return watchdog;
}

void writeSimReport(const SimOptions& o, const scene::Scene& scene, const gpu::Context& context,
                    const sim::Simulation& simulation, const SimTotals& totals, const std::string& watchdog,
                    double wallSeconds) {
  const sim::LatticeUnits& units = simulation.units();
  const glm::ivec3 size = scene.grid.size;
  // Memory-bound: the fraction of the device's copy bandwidth that the lattice update moves.
  const double bandwidth = gpu::measureCopyBandwidth(context);
  const double mlups = totals.updates / (totals.lbmMs * 1e3);
  const double lbmBandwidth = mlups * 1e6 * sim::bytesPerCellUpdate(scene.fluid.populationStorage) / 1e9;
  nlohmann::json obstacles = nlohmann::json::array();
  for (const nlohmann::json& f : totals.forcesPerObstacle)
    obstacles.push_back({{"force_lattice_per_step", f}});
  io::writeReport(
      o.report, {{"scene", scene.name},
                 {"device", context.properties().deviceName},
                 {"lattice", {size.x, size.y, size.z}},
                 {"smoke_upres", scene.grid.smokeUpres},
                 {"steps", simulation.step()},
                 {"steps_per_frame", units.stepsPerFrame},
                 {"step_seconds", units.stepSeconds},
                 {"tau", units.tau},
                 {"watchdog", watchdog},
                 {"mlups", mlups},
                 {"population_storage",
                  scene.fluid.populationStorage == scene::PopulationStorage::Fp16 ? "fp16" : "fp32"},
                 {"bytes_per_cell_update", sim::bytesPerCellUpdate(scene.fluid.populationStorage)},
                 {"lbm_bandwidth_gb_s", lbmBandwidth},
                 {"copy_bandwidth_gb_s", bandwidth},
                 {"bandwidth_fraction", lbmBandwidth / bandwidth},
                 {"lbm_ms", totals.lbmMs},
                 {"smoke_ms", totals.smokeMs},
                 {"gpu_ms", totals.totalMs},
                 {"wall_seconds", wallSeconds},
                 {"force_units", "lattice: rho0 = 1, cells/step^2; newtons = value * rho_air * dx^4 / dt^2"},
                 {"obstacles", obstacles},
                 {"frames", totals.frames}});
}

void run(const SimOptions& o) {
  const StopOnSignal stopOnSignal;
  const scene::Scene scene = scene::loadScene(o.scene);
  scene::requireSimulated(scene, o.scene.string());
  // --vdb-out is staged: an earlier run's frames stay whole until this run has succeeded; then those of this
  // scene name that this run did not replace go.
  const StagedDirectory::OutputNames vdbFrames = [&](const std::string& f) {
    return isFrameFileOf(scene.name, f);
  };
  checkOutputs(o, vdbFrames);
  std::optional<StagedDirectory> vdbOut;
  if (!o.vdbOut.empty()) vdbOut.emplace(o.vdbOut, "sim", o.force, vdbFrames);
  const Device device(o.common.deviceOptions());
  const gpu::Context& context = runtime::Access::context(device);
  const gpu::PipelineCache& cache = runtime::Access::pipelineCache(device);
  sim::Simulation simulation = withinDeviceLimits(o.scene.string(), gridSetting(scene.grid),
                                                  [&] { return sim::Simulation(context, cache, scene); });
  const sim::LatticeUnits& units = simulation.units();
  const glm::ivec3 size = scene.grid.size;
  std::printf("%s: %dx%dx%d lattice, %d steps per frame of %.4g s, tau %.5f, on %s\n", scene.name.c_str(),
              size.x, size.y, size.z, units.stepsPerFrame, scene.time.frameDt, units.tau,
              context.properties().deviceName);

  SimTotals totals;
  totals.forcesPerObstacle.assign(simulation.obstacles().obstacleCount(), nlohmann::json::array());
  const auto started = std::chrono::steady_clock::now();
  const std::string watchdog = simulate(o, scene, simulation, vdbOut, totals);
  const double wallSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (!o.report.empty()) writeSimReport(o, scene, context, simulation, totals, watchdog, wallSeconds);
  // A stopped simulation's frames are not moved in: an earlier run's stay whole, and a directory made for
  // this run goes again.
  if (watchdog != "ok") throw sim::WatchdogError(o.scene.string() + ": " + watchdog);
  if (vdbOut) vdbOut->commit();
}

}  // namespace

void addSimCommand(CLI::App& app) {
  auto o = std::make_shared<SimOptions>();
  CLI::App* command =
      app.add_subcommand("sim", "Run the smoke simulation (LBM + smoke transport) of a scene");
  o->common.addTo(*command);
  command->add_option("--scene", o->scene, "Scene JSON")->required()->check(filePath());
  command->add_option("--steps", o->steps, "Lattice steps")->required()->check(CLI::Range(1u, 100000000u));
  command
      ->add_option("--vdb-out", o->vdbOut,
                   "Write density and temperature per frame as OpenVDB (and the obstacles' triangles as "
                   "OBJ) into this directory")
      ->check(directoryPath());
  command
      ->add_option("--report", o->report,
                   "JSON report: forces on each obstacle, mass, max velocity, MLUPs, watchdog")
      ->check(filePath());
  command->add_flag("--force", o->force, "Overwrite an existing output directory or report");
  command->callback([o] { run(*o); });
}

}  // namespace sixway::app
