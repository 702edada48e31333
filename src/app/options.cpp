#include "app/options.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace sixway::app {

void CommonOptions::addTo(CLI::App& command) {
  command
      .add_option("--device", device,
                  "Vulkan device index (see `sixway info`); default: SIXWAY_DEVICE or the best")
      ->check(nonNegativeNumber());
  command.add_flag("--validate", validate,
                   "Vulkan validation layers on; every message is printed as 'validation: ...'");
}

namespace {

// "" when `text` is a value a float holds (or not a number at all: CLI11's conversion reports that).
std::string checkFloat(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0') return "";
  if (!std::isfinite(value)) return "must be a finite number (got " + text + ")";
  if (!std::isfinite(static_cast<float>(value)))
    return "is beyond the range of a 32-bit float, ±3.4e38 (got " + text + ")";
  if (value != 0 && static_cast<float>(value) == 0)
    return "is too small for a 32-bit float, which would make it 0 (got " + text + ")";
  return "";
}

// "" when `text` is a number (strtod reads all of it), else what is wrong.
std::string checkNumber(const std::string& text) {
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  if (end != text.c_str() && *end == '\0') return "";
  return "must be a number (got " + text + ")";
}

// A lower bound on a number; "" for text that is not a number (CLI11's conversion reports that).
CLI::Validator lowerBound(bool inclusive) {
  return CLI::Validator(
      [inclusive](const std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || std::isnan(value)) return "";
        if (inclusive ? value >= 0 : value > 0) return "";
        return std::string("must be ") + (inclusive ? ">= 0" : "> 0") + " (got " + text + ")";
      },
      inclusive ? "NUMBER >= 0" : "NUMBER > 0");
}

CLI::Validator nonEmptyPath(const std::string& kind) {
  return CLI::Validator(
      [kind](const std::string& text) -> std::string {
        return text.empty() ? "an empty path; give " + kind + "'s path" : "";
      },
      "");
}

}  // namespace

CLI::Validator filePath() {
  return nonEmptyPath("a file");
}

CLI::Validator directoryPath() {
  return nonEmptyPath("a directory");
}

CLI::Validator positiveNumber() {
  return lowerBound(false);
}

CLI::Validator nonNegativeNumber() {
  return lowerBound(true);
}

void requireFiniteNumbers(CLI::App& command) {
  const CLI::Validator finite(checkFloat, "");
  const CLI::Validator number(checkNumber, "");
  for (CLI::Option* option : command.get_options()) {
    const std::string type = option->get_type_name();
    const std::string base = type.substr(0, type.find(':'));
    if (base.find("FLOAT") != std::string::npos) option->check(finite);
    // First of all its checks (transform puts it in front), so that a range check does not call "abc" out of
    // range.
    if (base.find("FLOAT") != std::string::npos || base.find("INT") != std::string::npos)
      option->transform(number);
  }
}

DeviceOptions CommonOptions::deviceOptions() const {
  const char* forced = std::getenv("SIXWAY_VALIDATE");
  return {validate || (forced && std::string(forced) == "1"), device};
}

void requireNoValidationMessages(const Device& device) {
  if (device.validationMessages() > 0)
    throw std::runtime_error(std::to_string(device.validationMessages()) + " validation messages");
}

}  // namespace sixway::app
