#pragma once
// `sixway eval`: the quality of the neural lightmaps measured by our own pipeline (GLSL inference on the
// weights file). `--dataset DIR`: every sample of the chosen splits of a dataset (docs/dataset-format.md)
// against its reference lightmaps (the held-out metrics). `--scene S`: a scene's sequence, every
// method against the reference lightmaps and the path tracer, with timings (scene_eval.h).
#include <CLI/CLI.hpp>

namespace sixway::app {

void addEvalCommand(CLI::App& app);

}  // namespace sixway::app
