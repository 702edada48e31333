#pragma once
// `sixway dataset --config D --out DIR [--shard I/N]`: training pairs for the lightmap network — per
// simulated sequence, one shard of guiding maps, reference lightmaps and motion fields
// (docs/dataset-format.md).
#include <CLI/CLI.hpp>

namespace sixway::app {

void addDatasetCommand(CLI::App& app);

}  // namespace sixway::app
