#pragma once
// GPU time of one stage of a frame, from the timestamps sixway records around each stage.
#include <string>

namespace sixway {

struct StageTime {
  std::string name;  // "sim/lbm", "guide", "network", "shade", "shadow maps", ...
  double milliseconds;
};

}  // namespace sixway
