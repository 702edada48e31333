#pragma once
// Options every sixway command takes (docs/conventions.md, "Command line").
#include <sixway/device.h>
#include <CLI/CLI.hpp>

#include <optional>

namespace sixway::app {

struct CommonOptions {
  std::optional<int> device;  // --device N (else SIXWAY_DEVICE, else the best device)
  bool validate = false;      // --validate: Vulkan validation layers on

  void addTo(CLI::App& command);
  // The device every command runs on (SIXWAY_VALIDATE=1 validates it too: the tests set it).
  DeviceOptions deviceOptions() const;
};

// A command's last check: throws when the validation layer reported anything on `device`.
void requireNoValidationMessages(const Device& device);

// Adds a finiteness check to every floating-point option of `command` (call it after the options are added):
// CLI11's range checks compare with < and >, which NaN passes, and 1e39 or 1e-46 given to a float option
// becomes inf or 0 after the checks. Such a value is one error line naming the option. And, before every
// other check of a numeric option, that its value is a number ("--albedo: must be a number (got abc)", where
// CLI11's range check said "Value abc not in range").
void requireFiniteNumbers(CLI::App& command);

// Replace CLI11's PositiveNumber and NonNegativeNumber, whose messages print the largest double in 309
// digits:
// "--emission: must be >= 0 (got -1)".
CLI::Validator positiveNumber();
CLI::Validator nonNegativeNumber();

// For the options that take a file's or a directory's path: an empty value is refused, "--out: an empty
// path; give a directory's path" (an empty path was "'' is not a directory", "no such file", or no report).
CLI::Validator filePath();
CLI::Validator directoryPath();

}  // namespace sixway::app
