#pragma once
// The options of `sixway bake` (bake_command.h), as the command line gives them.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/options.h"

namespace sixway::app {

struct BakeOptions {
  CommonOptions common;
  std::filesystem::path scene, out, report;
  std::vector<std::filesystem::path> vdb;
  bool force = false, traceAllOrders = false;
  std::string scattering = "multiple";
  std::string packing = "unity";
  std::string emissive = "mask";
  std::optional<std::string> densityGrid;
  int first = 0;
  std::optional<int> frames, columns, voxels, samples, orders, downsample;
  std::optional<uint32_t> seed;
  std::string tile;
  std::vector<float> cameraPosition, cameraTarget, cameraUp;
  std::optional<float> fov, extinction, albedo, g, emission, step, lightSpacing;
};

}  // namespace sixway::app
