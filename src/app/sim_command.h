#pragma once
#include <CLI/CLI.hpp>

namespace sixway::app {

// `sixway sim`: runs a scene's smoke simulation; optional VDB frames and a JSON report.
void addSimCommand(CLI::App& app);

}  // namespace sixway::app
