#pragma once
#include <CLI/CLI.hpp>

namespace sixway::app {

// `sixway bake`: reference six-way lightmaps of a simulated scene or of OpenVDB files, as Unity-packed
// flipbooks (EXR, PNG, TGA) with a JSON sidecar and one EXR per frame.
void addBakeCommand(CLI::App& app);

}  // namespace sixway::app
