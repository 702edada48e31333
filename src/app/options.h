#pragma once
// Options every sixway command takes (docs/conventions.md, "Command line").
#include <CLI/CLI.hpp>

#include <optional>

#include "gpu/context.h"

namespace sixway::app {

struct CommonOptions {
  std::optional<int> device;  // --device N (else SIXWAY_DEVICE, else the best device)
  bool validate = false;      // --validate: Vulkan validation layers on

  void addTo(CLI::App& command);
  gpu::ContextOptions contextOptions() const;
};

}  // namespace sixway::app
