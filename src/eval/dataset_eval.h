#pragma once
// `sixway eval --dataset`: the network on the samples of a dataset's shards (`sixway dataset`,
// docs/dataset-format.md), its lightmaps against the shards' targets per split (lightmap PSNR,
// docs/conventions.md, "Metrics"), and its inference time.
#include <sixway/device.h>

#include <filesystem>
#include <string>
#include <vector>

namespace sixway::eval {

struct DatasetEvalSettings {
  std::filesystem::path dataset, weights, report;
  std::vector<std::string> splits;  // the samples' splits evaluated
  std::string target;               // the shards' targets compared with: single or multiple scattering
  bool force = false;               // overwrite an existing report
};

// On sixway's own device of `device`.
void evaluateDataset(const DeviceOptions& device, const DatasetEvalSettings& settings);

}  // namespace sixway::eval
