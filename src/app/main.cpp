// sixway: the command line (docs/conventions.md, "Command line"). Every failure ends in one line on stderr
// and exit 1; a run stopped by SIGINT or SIGTERM ends by that signal.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "app/bake_command.h"
#include "app/bench_command.h"
#include "app/dataset_command.h"
#include "app/eval_command.h"
#include "app/info_command.h"
#include "app/options.h"
#include "app/process_memory.h"
#include "app/render_command.h"
#include "app/sim_command.h"
#include "app/stop_on_signal.h"

int main(int argc, char** argv) {
  sixway::app::oneMallocArenaUnderAddressLimit();
  CLI::App app("sixway: real-time smoke rendering with neural six-way lightmaps");
  app.require_subcommand(1);
  sixway::app::addInfoCommand(app);
  sixway::app::addSimCommand(app);
  sixway::app::addBakeCommand(app);
  sixway::app::addBenchCommand(app);
  sixway::app::addRenderCommand(app);
  sixway::app::addDatasetCommand(app);
  sixway::app::addEvalCommand(app);
  const std::vector<CLI::App*> commands = app.get_subcommands({});
  for (CLI::App* command : commands) sixway::app::requireFiniteNumbers(*command);
  // A mistyped command: CLI11 would say only "A subcommand is required".
  if (argc > 1 && argv[1][0] != '-' &&
      std::ranges::none_of(commands, [&](CLI::App* command) { return command->check_name(argv[1]); })) {
    std::string names;
    for (const CLI::App* command : commands) names += (names.empty() ? "" : ", ") + command->get_name();
    std::fprintf(stderr, "sixway: error: unknown command '%s' (the commands: %s)\n", argv[1], names.c_str());
    return 109;  // CLI11's exit code for an unexpected argument
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    // A bad option is one line too (CLI11's own adds "Run with --help ..."); CLI11's exit code is kept.
    std::fprintf(stderr, "sixway: error: %s\n", e.what());
    return e.get_exit_code();
  } catch (const sixway::app::Stopped& e) {
    // The outputs are cleaned up by now: end by the signal, as a shell expects of an interrupted command.
    std::fprintf(stderr, "sixway: %s\n", e.what());
    std::signal(e.signal(), SIG_DFL);
    std::raise(e.signal());
    return 128 + e.signal();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sixway: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
