#pragma once
#include <CLI/CLI.hpp>

namespace sixway::app {

// Registers the commands of DESIGN.md §5 whose stages are still being built, with their
// options, so scripts see the final interface; running one says which issue brings it.
void addPlannedCommands(CLI::App& app);

}  // namespace sixway::app
