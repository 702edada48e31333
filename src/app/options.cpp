#include "app/options.h"

#include <cstdlib>
#include <string>

namespace sixway::app {

void CommonOptions::addTo(CLI::App& command) {
  command
      .add_option("--device", device,
                  "Vulkan device index (see `sixway info`); default: SIXWAY_DEVICE or the best")
      ->check(CLI::NonNegativeNumber);
  command.add_flag("--validate", validate,
                   "Vulkan validation layers on; every message is printed as 'validation: ...'");
}

gpu::ContextOptions CommonOptions::contextOptions() const {
  gpu::ContextOptions options;
  options.deviceIndex = device;
  // Tests set SIXWAY_VALIDATE=1 so that every GPU run they make is validated.
  const char* forced = std::getenv("SIXWAY_VALIDATE");
  options.validate = validate || (forced && std::string(forced) == "1");
  return options;
}

}  // namespace sixway::app
