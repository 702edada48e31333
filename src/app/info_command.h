#pragma once
#include <CLI/CLI.hpp>

namespace sixway::app {

// `sixway info`: the Vulkan device and the limits the stages depend on.
void addInfoCommand(CLI::App& app);

}  // namespace sixway::app
