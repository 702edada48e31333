#pragma once
// `sixway eval`: the quality of the neural lightmaps measured by our own pipeline (GLSL inference on the
// weights file). `--dataset DIR`: every sample of the chosen splits of a dataset (docs/dataset-format.md)
// against its reference lightmaps (issue #7's held-out metrics). `--scene` (whole sequences against the
// references and the path tracer) arrives with issue #9.
#include <CLI/CLI.hpp>

namespace sixway::app {

void addEvalCommand(CLI::App& app);

}  // namespace sixway::app
