#pragma once
#include <CLI/CLI.hpp>

namespace sixway::app {

// `sixway bench`: GPU timings per stage at fixed sizes (warm-up, then the median of repeated submits),
// printed and written as a JSON report. Each stage that can be benchmarked is one section of the list in
// bench_command.cpp; the network's section times every layer.
void addBenchCommand(CLI::App& app);

}  // namespace sixway::app
