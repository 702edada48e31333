#include "app/planned_commands.h"

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "app/options.h"

namespace sixway::app {
namespace {

// The options are parsed and checked like a real command's, then the command refuses to run.
struct PlannedOptions {
  CommonOptions common;
  std::filesystem::path scene, out, report, config;
  int steps = 0, frames = 0;
  std::string shard;
  bool force = false;
};

CLI::App* planned(CLI::App& app, const char* name, const char* description, const char* issue,
                  std::shared_ptr<PlannedOptions> options) {
  CLI::App* command = app.add_subcommand(name, description);
  options->common.addTo(*command);
  command->callback([name, issue] {
    throw std::runtime_error(std::string("'sixway ") + name + "' is not built yet: it arrives with issue " +
                             issue);
  });
  return command;
}

}  // namespace

void addPlannedCommands(CLI::App& app) {
  auto o = std::make_shared<PlannedOptions>();
  CLI::App* dataset = planned(app, "dataset", "Training pairs: guiding map → reference lightmaps",
                              "#7 (training data and weights)", o);
  dataset->add_option("--config", o->config, "Dataset config JSON")->required();
  dataset->add_option("--out", o->out, "Output directory")->required();
  dataset->add_option("--shard", o->shard, "I/N: this job's share of the work");

  CLI::App* eval = planned(app, "eval", "PSNR/MSE against the references, timings per stage",
                           "#9 (evaluation and benchmarks)", o);
  eval->add_option("--scene", o->scene, "Scene JSON")->required();
  eval->add_option("--frames", o->frames, "Frames")->required()->check(CLI::PositiveNumber);
  eval->add_option("--report", o->report, "JSON report")->required();
}

}  // namespace sixway::app
