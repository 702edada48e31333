#pragma once
// The networks shipped in weights/ (weights/README.md) and how --weights names them.
#include <filesystem>

namespace sixway::app {

// Help text of every command's --weights option.
inline constexpr const char* kWeightsHelp =
    "Network file, or ms / ss for the shipped all-orders / single-scattering network (default ms)";

// `given` as --weights names it: empty is the default (the all-orders network), `ms` and `ss` are the shipped
// networks (a file of that name in the working directory is ./ms), anything else a file path, unchanged.
std::filesystem::path resolveWeights(const std::filesystem::path& given);

}  // namespace sixway::app
