#pragma once
// `sixway render --scene S --frames N --out DIR [--mode M]`: headless frame capture
// (docs/real-time-rendering.md).
#include <CLI/CLI.hpp>

namespace sixway::app {

void addRenderCommand(CLI::App& app);

}  // namespace sixway::app
